"""Optimisation synthesis of lever mechanisms (blocks B1-B5, Peisakh criteria), the built-in
cases and the command line. Uses only the public API of :mod:`assur`.

The library, for a script or a notebook::

    from synthesis import load_problem, synthesize
    result = synthesize(load_problem("problem.yaml"), seed=0)
    result.design, result.q, result.feasible, result.to_dict()

:func:`load_problem` reads a problem table (B1), :func:`synthesize` searches it (B2–B4) and
returns a frozen :class:`SynthesisResult` (B5); :class:`SearchSettings` holds the options of
the search.  The names are imported on first use, so that the command line, which lives in
this package, starts without loading the search (SciPy).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from synthesis.outcome import SynthesisResult, synthesize
    from synthesis.problem import Problem
    from synthesis.problem_table import load_problem, problem_from_dict
    from synthesis.search_result import SearchResult
    from synthesis.search_settings import SearchSettings, SettingError

__all__ = ["Problem", "SearchResult", "SearchSettings", "SettingError", "SynthesisResult",
           "load_problem", "problem_from_dict", "synthesize"]


def __getattr__(name: str) -> object:
    """The public names, each from the module that defines it (PEP 562)."""
    if name == "Problem":
        from synthesis.problem import Problem
        return Problem
    if name in ("load_problem", "problem_from_dict"):
        from synthesis import problem_table
        return getattr(problem_table, name)
    if name == "SearchResult":
        from synthesis.search_result import SearchResult
        return SearchResult
    if name in ("SearchSettings", "SettingError"):
        from synthesis import search_settings
        return getattr(search_settings, name)
    if name in ("SynthesisResult", "synthesize"):
        from synthesis import outcome
        return getattr(outcome, name)
    raise AttributeError(f"module 'synthesis' has no attribute {name!r}")
