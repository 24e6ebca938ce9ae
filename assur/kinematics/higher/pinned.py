"""A triad without a bar whose P–P leash fixes its rotation: one mode, in closed form.

A leash that slides on a guide of the base and on a guide of a known link K turns with both,
so the base turns with K (θ = θ_K). Without a bar the other two leashes (R–P or P–R) are then
two lines in the position P₁ of the base, and P₁ is where they cross: exactly one mode at
every position, the lines' crossing (``docs/higher_groups.md``, "A P–P leash"). There is
nothing to follow and no mode to jump to: the positions are solved at every crank angle at
once, the analogs by implicit differentiation as for every triad. Where the two lines turn
parallel the base runs off to infinity and comes back from the other side; the group does
not exist where the margin (the sine of the angle between the lines, scaled as in §1.7) is
below δ, with the dyads' reason "guides parallel".
"""

from __future__ import annotations

import numpy as np

from assur.kinematics import jets as J
from assur.kinematics.higher.continuation import (
    HigherSolution,
    analogs,
    finite_inputs,
)
from assur.kinematics.higher.groups import (
    Triad,
    TriadInputs,
    expand,
    hadamard,
    plain,
    values,
)
from assur.kinematics.higher.modes import assembly_modes, select_mode
from assur.kinematics.jets import Jet
from assur.kinematics.reasons import Reason
from assur.typing import Value

__all__ = ["place"]


def place(group: Triad, k0: TriadInputs, k: TriadInputs, *, delta: float | np.ndarray = 0.0
          ) -> HigherSolution:
    """The one mode of a triad with a P–P leash and no bar at every position.

    Parameters
    ----------
    group : Triad
        Leashes (R–P or P–R, R–P or P–R, P–P); drawn values of shape () or (D,).
    k0 : TriadInputs
        The inputs at the sketch position (plain values of shape () or (D,)).
    k : TriadInputs
        The inputs at the N positions, shape (N,) or (D, N): plain arrays, or jets in the
        crank angle for the analogs.
    delta : float or ndarray
        The assigned tolerance: the group exists where ``margin >= delta``.

    Returns
    -------
    HigherSolution
        As :func:`~assur.kinematics.higher.continuation.follow_mode` gives it: the joints and
        rotations (jets when ``k`` holds jets), the margin, ``exists`` and the reason (0; 5
        where the two lines are parallel within δ; 7 where an input is undefined; 9 where
        the sketch picks no mode); no ends, closed.

    Examples
    --------
    A crank at the origin carries the guide of the P–P leash, so the base turns with it; the
    blocks hinged at P1 and P2 slide on the frame's lines x = 40 and y = 30:

    >>> from assur.kinematics.jets import expi
    >>> u = np.exp(0.25j * np.pi)
    >>> g = Triad(("RP", "RP", "PP"), (40 + 0j, 50 + 30j, 60 + 10j),
    ...           (40 + 0j, 50 + 30j, 60 + 10j), (1j, 1 + 0j, u))
    >>> k0 = TriadInputs((40 + 0j, 50 + 30j, 60 + 10j), (1j, 1 + 0j, u))
    >>> phi = np.radians([0.0, 30.0])
    >>> k = TriadInputs((40 + 0j, 50 + 30j, (60 + 10j) * expi(phi)), (1j, 1 + 0j, u * expi(phi)))
    >>> sol = place(g, k0, k)
    >>> np.round(sol.joints["P1"], 6).tolist(), np.round(sol.joints["P2"].imag, 9).tolist()
    ([(40+0j), (40-0.980762j)], [30.0, 30.0])
    """
    modes = assembly_modes(group, k0)
    _, found = select_mode(group, k0, modes)
    wide, kv = expand(group), values(k)
    defined = finite_inputs(kv)
    with np.errstate(all="ignore"):
        x = wide.recover(np.ones(np.shape(kv.a[0])), kv)
        margin = np.where(defined, hadamard(wide.lines(x, kv)[1]), np.nan)
    exists = np.asarray(found)[..., None] & defined & (margin >= np.asarray(delta)[..., None])
    reason = np.where(~defined, Reason.UNDEFINED_INPUT,
                      np.where(~np.asarray(found)[..., None], Reason.NOT_FOLLOWED,
                               np.where(exists, 0, Reason.GUIDES_PARALLEL))).astype(np.int8)
    jets = any(isinstance(v, Jet) for v in (*k.a, *k.u))
    cols: list[Jet | np.ndarray] = [x[..., i] for i in range(3)]
    if jets:
        with np.errstate(all="ignore"):
            x1, x2 = analogs(wide, k, x)
        cols = [Jet(x[..., i], x1[..., i], x2[..., i]) for i in range(3)]

    def blank(v: Value) -> Jet | np.ndarray:
        """NaN where the group does not exist; a jet (a fixed input's with zero analogs)
        when the inputs are jets."""
        if jets:
            jet = J.as_jet(v)
            return Jet(*(np.where(exists, part, np.nan) for part in (jet.v, jet.d1, jet.d2)))
        return np.where(exists, plain(v), np.nan)

    design = np.shape(found)
    return HigherSolution(
        joints={a: blank(b) for a, b in wide.joints(cols, k).items()},
        rotations={a: blank(b) for a, b in wide.rotations(cols, k).items()},
        x=np.where(exists[..., None], x, np.nan), margin=margin, exists=exists, reason=reason,
        ends=np.full(design + (2,), np.nan), end_reasons=np.zeros(design + (2,), dtype=np.int8),
        closed=np.ones(design, dtype=bool), found=np.asarray(found), modes=modes)
