"""Built-in case: the rhomboid orientation mechanism of a solar tracker (patent application
RO a 2010 00677), driven by a linear actuator.

Modules: :mod:`geometry` (closed forms), :mod:`patent` (printed values), :mod:`design`
(Etapa I–VI), :mod:`model` (kinematics on the group solvers), :mod:`study` (one task end to
end), :mod:`reproduction`, :mod:`report`, :mod:`plot`, :mod:`task` (the input table) and
:mod:`cli` (``assur case tracker``).
"""
