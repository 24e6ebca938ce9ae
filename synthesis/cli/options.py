"""Checks of command-line options that the argument parser cannot state: every bad option
at once, each message naming the option, exit code 2; and the bounds of the machine
(``--scheduler local:N`` and ``--jobs`` at most its cores).

The search options are checked by the very rules of the problem table's ``search:`` section
(:func:`synthesis.search.setting_problem`), so an option and a table entry can never disagree.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Mapping
from dataclasses import dataclass

from assur.errors import AssurError
from assur.io.reader import LARGEST, SMALLEST
from assur.text import Message, render

__all__ = ["AT", "FRAMES", "MAX_FRAMES", "MAX_POINTS", "OMEGA", "OptionError", "Range",
           "bounded_jobs", "check_at_least", "check_ranges", "check_scheduler",
           "check_search_options", "points_range"]

#: The most positions of the input cycle a command analyses (about 10 MB of results for a
#: six-bar; 10⁸ would not fit in memory).
MAX_POINTS = 100_000
#: The most frames of an animation.
MAX_FRAMES = 3_600


class OptionError(AssurError):
    """Command-line options out of their range (every one at once)."""

    def __init__(self, problems: list[tuple[str, Message]]) -> None:
        self.problems = problems
        super().__init__(self.text("en"))

    def text(self, lang: str = "en") -> str:
        """One line per option, in ``lang``."""
        return "\n".join(f"{option}: {message.text(lang)}" for option, message in self.problems)


@dataclass(frozen=True, slots=True)
class Range:
    """The range of a numeric option: ``low ≤ value ≤ high``, finite, whole when ``whole``.

    Examples
    --------
    >>> OMEGA.problem(float("nan")).text("en")
    'expected a finite number from 1e-12 to 1e+09; found nan'
    >>> Range(1, 10, whole=True).problem(0).text("en")
    'expected a whole number from 1 to 10; found 0'
    >>> OMEGA.problem(10.0) is None
    True
    """

    low: float
    high: float
    whole: bool = False

    def problem(self, value: float) -> Message | None:
        """What is wrong with ``value`` (None when it is in range)."""
        if math.isfinite(value) and self.low <= value <= self.high:
            return None
        code = "cli.option.whole_range" if self.whole else "cli.option.number_range"
        return Message(code, {"low": self.low, "high": self.high, "found": value})


#: ``--omega``: the input speed, rad/s of a crank or mm/s of an actuator (the rule of a size
#: of a table, as for ``general: omega``).
OMEGA = Range(SMALLEST, LARGEST)
#: ``--at``: the crank angle (degrees) or actuator length (mm) of the drawn position.
AT = Range(-LARGEST, LARGEST)
#: ``--frames``: the frames of an animation.
FRAMES = Range(1, MAX_FRAMES, whole=True)


def points_range(lowest: int) -> Range:
    """``--points``: from ``lowest`` to :data:`MAX_POINTS` positions."""
    return Range(lowest, MAX_POINTS, whole=True)


def check_ranges(args: argparse.Namespace, ranges: Mapping[str, Range]) -> None:
    """Refuse every option (destination → range) that is given and outside its range.

    Raises
    ------
    OptionError

    Examples
    --------
    >>> args = argparse.Namespace(omega=float("inf"), points=10**11, at=None)
    >>> check_ranges(args, {"omega": OMEGA, "points": points_range(2), "at": AT})
    Traceback (most recent call last):
    ...
    synthesis.cli.options.OptionError: --omega: expected a finite number from 1e-12 to 1e+09; found inf
    --points: expected a whole number from 2 to 100000; found 100000000000
    """
    problems = []
    for dest, rule in ranges.items():
        value = getattr(args, dest, None)
        message = None if value is None else rule.problem(value)
        if message is not None:
            problems.append((f"--{dest.replace('_', '-')}", message))
    if problems:
        raise OptionError(problems)


def check_at_least(**options: tuple[int | None, int]) -> None:
    """Refuse every option (``name=(value, lowest)``) below its lowest value.

    Raises
    ------
    OptionError

    Examples
    --------
    >>> check_at_least(jobs=(2, 1))
    >>> check_at_least(jobs=(0, 1), points=(3, 8))
    Traceback (most recent call last):
    ...
    synthesis.cli.options.OptionError: --jobs: expected a whole number ≥ 1; found 0
    --points: expected a whole number ≥ 8; found 3
    """
    problems = [(f"--{name.replace('_', '-')}", Message("cli.option.at_least",
                                                        {"low": low, "found": value}))
                for name, (value, low) in options.items() if value is not None and value < low]
    if problems:
        raise OptionError(problems)


def check_search_options(args: argparse.Namespace, fields: Mapping[str, str]) -> None:
    """Refuse every search option that breaks the rule of its setting.

    Parameters
    ----------
    args : argparse.Namespace
    fields : mapping
        Option destination → field of :class:`synthesis.search.SearchSettings`.

    Raises
    ------
    OptionError
    """
    from synthesis.search_settings import setting_problem

    problems = []
    for dest, name in fields.items():
        value = getattr(args, dest, None)
        message = None if value is None else setting_problem(name, value)
        if message is not None:
            problems.append((f"--{dest.replace('_', '-')}", message))
    if problems:
        raise OptionError(problems)


def check_scheduler(spec: str | None) -> None:
    """Refuse a misnamed ``--scheduler`` before anything starts (Dask is not imported).

    Raises
    ------
    synthesis.distributed.DistributedError
        Naming ``--scheduler``, what is expected and what was found (exit code 2).

    Examples
    --------
    >>> check_scheduler(None), check_scheduler("local:1"), check_scheduler("tcp://[::1]:8786")
    (None, None, None)
    >>> check_scheduler("tcp://:::")
    Traceback (most recent call last):
    ...
    synthesis.distributed.DistributedError: --scheduler 'tcp://:::': expected a host name, \
an IPv4 address or an IPv6 address in brackets ([::1]); found '::'
    """
    if spec is not None:
        from synthesis.distributed import parse_scheduler

        parse_scheduler(spec)


def bounded_jobs(jobs: int | None, lang: str = "en") -> int | None:
    """``--jobs`` lowered to the cores of this machine, with a warning when it was above.

    Parameters
    ----------
    jobs : int or None
        The option (None: the default, all the cores).
    lang : str
        The language of the warning, printed on standard error.

    Returns
    -------
    int or None
        ``jobs``, or the number of cores when ``jobs`` exceeds it.

    Examples
    --------
    >>> from synthesis.distributed import usable_cores
    >>> bounded_jobs(None), bounded_jobs(1)
    (None, 1)
    >>> bounded_jobs(100_000) == usable_cores()
    True
    """
    from synthesis.distributed import usable_cores

    most = usable_cores()
    if jobs is None or jobs <= most:
        return jobs
    print(render("cli.option.clamped", lang, option="--jobs", found=jobs, most=most),
          file=sys.stderr)
    return most
