"""The ``assur`` command: the console script's entry point, kept tiny.

Everything else is imported inside the guard, so Ctrl-C pressed while the program is still
loading ends with the interrupted message and exit code 130 like at any other moment, never a
traceback.  The commands and the exit codes: :mod:`synthesis.cli.boundary`.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from contextlib import suppress

__all__ = ["main"]


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code."""
    try:
        from synthesis.cli.boundary import run

        return run(argv)
    except KeyboardInterrupt:
        with suppress(KeyboardInterrupt, OSError):  # a second Ctrl-C: leave quietly
            from assur.text import render

            print(render("cli.interrupted"), file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
