"""The one place where a run of ``assur`` ends: every outcome becomes a message and an exit code.

Exit codes (the same for every command):

* 0 — the run finished (whatever it found);
* 1 — a search ended without a feasible design;
* 2 — invalid input or an output that could not be written where asked (the message names
  the file, table, row and field, or the path and where the result went instead);
* 3 — an internal error: one line naming the input and asking for a bug report (the
  traceback only with ``--debug``);
* 130 — interrupted by Ctrl-C, at any moment; a search that had started writes its best
  design first;
* 141 — standard output was closed early (``assur analyze … | head``): nothing more is
  printed, as for any command killed by a closed pipe.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
import traceback
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from types import FrameType

from assur.errors import AssurError
from assur.text import render
from synthesis.app.outputs import OutputError, Outputs, output_problem
from synthesis.cli.parser import build_parser

__all__ = ["BUG", "CLOSED_PIPE", "INTERRUPTED", "INVALID", "run"]

INVALID = 2
BUG = 3
INTERRUPTED = 130
CLOSED_PIPE = 141
#: The arguments that name a command's input, for the line of an internal error.
_INPUTS = ("table", "problem", "folder")


class _Interrupts:
    """Ctrl-C noted even when the code it interrupts catches it (a search keeps its best)."""

    def __init__(self) -> None:
        self.seen = False

    def handle(self, _signum: int, _frame: FrameType | None) -> None:
        self.seen = True
        raise KeyboardInterrupt

    @contextmanager
    def watching(self) -> Iterator[None]:
        """Install the handler for the ``with`` block (in the main thread only)."""
        if threading.current_thread() is not threading.main_thread():
            yield
            return
        previous = signal.signal(signal.SIGINT, self.handle)
        try:
            yield
        finally:
            signal.signal(signal.SIGINT, previous)


def _check_outputs(args: argparse.Namespace) -> None:
    """Refuse, before the run, every output path that cannot be written."""
    wanted = getattr(args.module, "OUTPUTS", {})
    problems = [output_problem("--" + dest.replace("_", "-"), getattr(args, dest), kind)
                for dest, kind in wanted.items() if getattr(args, dest, None)]
    found = [p for p in problems if p is not None]
    if found:
        raise OutputError(found)


def _silence_stdout() -> None:
    """Point standard output at the null device so that the final flush cannot fail."""
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass


def _input_of(args: argparse.Namespace | None) -> str:
    for name in _INPUTS:
        value = getattr(args, name, None)
        if value:
            return str(value)
    return "-"


def run(argv: Sequence[str] | None = None) -> int:
    """Parse ``argv``, run the command, and turn every outcome into an exit code.

    Parameters
    ----------
    argv : sequence of str, optional
        Default ``sys.argv[1:]``.

    Returns
    -------
    int
        The exit code (see the module's description).
    """
    words = list(sys.argv[1:] if argv is None else argv)
    args: argparse.Namespace | None = None
    lang = "en"
    interrupts = _Interrupts()
    try:
        with interrupts.watching():
            args = build_parser(words).parse_args(words)
            lang = getattr(args, "lang", "en")
            _check_outputs(args)
            args.outputs = Outputs(lang)
            code = int(args.handler(args))
            sys.stdout.flush()
        if args.outputs.failures:
            print(args.outputs.text(), file=sys.stderr)
            code = INVALID
        if interrupts.seen:
            print(render("cli.interrupted", lang), file=sys.stderr)
            code = INTERRUPTED
        return code
    except AssurError as exc:
        print(exc.text(lang), file=sys.stderr)
        return INVALID
    except KeyboardInterrupt:
        print(render("cli.interrupted", lang), file=sys.stderr)
        return INTERRUPTED
    except BrokenPipeError:
        _silence_stdout()
        return CLOSED_PIPE
    except Exception as exc:  # noqa: BLE001 - the boundary: any other failure is a bug
        print(render("cli.bug", lang, file=_input_of(args), error=type(exc).__name__, flag="--debug",
                     detail=str(exc)[:200]), file=sys.stderr)
        if getattr(args, "debug", False) or "--debug" in words:
            traceback.print_exc()
        return BUG
