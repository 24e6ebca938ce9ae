"""Progress bars of the long runs on standard error: total, best so far and time left.

One adapter for every command that can run longer than a second or two (``synthesize``,
``batch``, ``report`` of a problem, the cases that search): the bars are drawn by
`tqdm <https://tqdm.github.io>`_, a well-kept library that measures the rate and the time
left, fits the terminal's width and redraws one line in place.  A bar appears only after
:data:`DELAY` seconds, only when standard error is a terminal and never with ``--quiet``,
so a grading script, a pipe or a log file receives no progress at all.

Examples
--------
>>> import io
>>> with counting(3, "progress.batch", quiet=False, stream=io.StringIO()) as bar:
...     for _ in range(3):
...         bar.advance()
>>> bar.done
3
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, TextIO

from assur.text import render

if TYPE_CHECKING:
    from tqdm import tqdm

    from synthesis.criteria import Criteria

__all__ = ["DELAY", "REDRAW", "Bar", "counting", "following_search", "shown"]

#: Seconds a run lasts before its bar appears (short runs draw nothing).
DELAY = 1.0
#: Least seconds between two redraws of a bar.
REDRAW = 0.1


def shown(quiet: bool, stream: TextIO | None = None) -> bool:
    """Whether a bar is drawn: not ``quiet`` and the stream (standard error) is a terminal.

    Examples
    --------
    >>> import io
    >>> shown(False, io.StringIO()), shown(True, io.StringIO())
    (False, False)
    """
    stream = sys.stderr if stream is None else stream
    isatty = getattr(stream, "isatty", None)
    return not quiet and callable(isatty) and bool(isatty())


class Bar:
    """One bar: a count of done items out of a total, and a note (the best so far).

    Parameters
    ----------
    total : int
        The items planned (the bar grows its total when more come).
    label : str
        The words in front of the bar.
    show : bool
        Draw it (see :func:`shown`); a hidden bar only counts.
    stream : text stream, optional
        Where to draw (default standard error).
    """

    def __init__(self, total: int, label: str, *, show: bool,
                 stream: TextIO | None = None) -> None:
        self.done = 0
        self.total = total
        self._bar: tqdm[None] | None = None
        if show:
            from tqdm import tqdm

            self._bar = tqdm(total=total, desc=label, file=stream or sys.stderr,
                             delay=DELAY, mininterval=REDRAW, leave=False,
                             dynamic_ncols=True)

    def advance(self, count: int = 1) -> None:
        """Count ``count`` more items done."""
        self.move_to(self.done + count)

    def move_to(self, done: int, total: int | None = None, note: str | None = None) -> None:
        """Set the items done (and the total, and the note after the bar)."""
        total = max(done, self.total if total is None else total)
        self.done, self.total = done, total
        if self._bar is None:
            return
        self._bar.total = total
        if note is not None:
            self._bar.set_postfix_str(note, refresh=False)
        self._bar.update(done - self._bar.n)

    def close(self) -> None:
        """Remove the bar from the terminal."""
        if self._bar is not None:
            self._bar.close()


@contextmanager
def counting(total: int, label_code: str, *, quiet: bool, lang: str = "en",
             stream: TextIO | None = None) -> Iterator[Bar]:
    """A bar for ``total`` items named by the catalogue entry ``label_code``.

    Parameters
    ----------
    total : int
    label_code : str
        The catalogue code of the label (``progress.batch``, …).
    quiet : bool
        ``--quiet``: no bar.
    lang : str
        A catalogue language.
    stream : text stream, optional
        Default standard error.

    Yields
    ------
    Bar
    """
    bar = Bar(total, render(label_code, lang), show=shown(quiet, stream), stream=stream)
    try:
        yield bar
    finally:
        bar.close()


def _best(criteria: Criteria | None, lang: str) -> str:
    if criteria is None:
        return ""
    return render("progress.best", lang, p1=float(criteria.p1[0]), p2=float(criteria.p2[0]),
                  q=float(criteria.q[0]))


@contextmanager
def following_search(*, quiet: bool, lang: str = "en",
                     stream: TextIO | None = None) -> Iterator[Bar]:
    """Draw a bar for every search that runs inside the ``with`` block.

    The search (:data:`synthesis.search.LISTENER`) reports its trials, the trials it
    plans and its best design; the bar shows them with the time left.  ``quiet``, ``lang``
    and ``stream`` as for :func:`counting` (with ``quiet`` the search prints nothing).

    Yields
    ------
    Bar
        The bar of the search (counts even when hidden).
    """
    from synthesis.search import LISTENER

    with counting(0, "progress.search", quiet=quiet, lang=lang, stream=stream) as bar:
        def listen(trials: int, planned: int, best: Criteria | None, _seconds: float) -> None:
            bar.move_to(trials, planned, _best(best, lang))

        token = LISTENER.set(listen)
        try:
            yield bar
        finally:
            LISTENER.reset(token)
