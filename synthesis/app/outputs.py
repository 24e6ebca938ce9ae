"""Output files of a command: checked before the run, announced once, never lost.

A long run must not end in a traceback because its result cannot be written.  So:

* :func:`output_problem` checks a path before the run starts: a folder given where a file
  belongs, a path under a file, a folder the program may not write into (tried by creating
  and removing a temporary file, which is what decides, whoever runs the program).  Missing
  folders are no problem: they are created.
* :class:`Outputs` writes each file and prints one ``written: PATH`` line.  If writing still
  fails (the disk filled up during the run), the result is saved in the first place that
  takes it — next to the requested path, in the current folder, in the temporary folder —
  or, for a text, printed on standard output; the failure and where the result went are kept
  for the command line, which reports them and exits with code 2.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TextIO, TypeVar

from assur.errors import AssurError
from assur.text import Message, render

__all__ = ["STDOUT", "OutputError", "Outputs", "output_problem", "outputs_of", "stdout_taken"]

T = TypeVar("T")

#: What an output option names: a file, or a folder that receives files.
FILE, FOLDER = "file", "folder"
#: The name of a text output (``--csv -``) that goes to standard output.
STDOUT = "-"


def stdout_taken(args: argparse.Namespace, option: str) -> bool:
    """Whether the text output ``option`` (a destination of ``args``) goes to standard output,
    which then carries it alone: with ``--json`` as well, the two answers would mix, and both
    are refused.

    Raises
    ------
    OutputError
        When ``--json`` is asked for too.
    """
    if getattr(args, option, None) != STDOUT:
        return False
    if getattr(args, "json", False):
        raise OutputError([Message("cli.output.stdout_twice",
                                   {"option": f"--{option}", "json": "--json"})])
    return True


class OutputError(AssurError):
    """Output paths that cannot be written, found before the run (every one at once)."""

    def __init__(self, messages: list[Message]) -> None:
        self.messages = messages
        super().__init__(self.text("en"))

    def text(self, lang: str = "en") -> str:
        """One line per path, in ``lang``."""
        return "\n".join(m.text(lang) for m in self.messages)


def _existing_ancestor(path: Path) -> Path:
    """The nearest folder or file above ``path`` (or ``path`` itself) that exists."""
    for candidate in (path, *path.parents):
        if os.path.lexists(candidate):
            return candidate
    return Path(".")


def _cannot_create_in(folder: Path) -> str | None:
    """Why no file can be created in ``folder`` (None when one can)."""
    import tempfile  # with the modules it loads, only by a command that writes a file

    try:
        handle, name = tempfile.mkstemp(prefix=".assur-probe.", dir=folder)
    except OSError as exc:
        return exc.strerror or type(exc).__name__
    os.close(handle)
    os.unlink(name)
    return None


def output_problem(option: str, path: str | os.PathLike[str], kind: str = FILE
                   ) -> Message | None:
    """Why ``path`` cannot receive an output, or None when it can.

    Parameters
    ----------
    option : str
        The command-line option that named the path (``--out``), for the message.
    path : path-like
        The requested file (``kind='file'``) or folder (``kind='folder'``).
    kind : {'file', 'folder'}

    Returns
    -------
    Message or None

    Examples
    --------
    >>> import tempfile, pathlib
    >>> here = pathlib.Path(tempfile.mkdtemp())
    >>> output_problem("--out", here / "new" / "result.yaml") is None
    True
    >>> print(output_problem("--out", here).text("en"))  # doctest: +ELLIPSIS
    --out ...: this is a folder; give a file name in it
    """
    if kind == FILE and str(path) == STDOUT:
        return None
    target = Path(path)
    data = {"option": option, "path": str(target)}
    if kind == FILE and target.is_dir():
        return Message("cli.output.is_folder", data)
    if kind == FOLDER and target.exists() and not target.is_dir():
        return Message("cli.output.not_folder", data)
    base = _existing_ancestor(target if kind == FOLDER else target.parent)
    if not base.is_dir():
        return Message("cli.output.under_file", {**data, "file": str(base)})
    if kind == FILE and target.exists() and not os.access(target, os.W_OK):
        return Message("cli.output.cannot_write", {**data, "folder": str(target),
                                                   "reason": os.strerror(13)})
    reason = _cannot_create_in(base)
    if reason is not None:
        return Message("cli.output.cannot_write", {**data, "folder": str(base),
                                                   "reason": reason})
    return None


def _fallbacks(path: Path) -> Iterator[Path]:
    """Where a result goes when its path fails: next to it, here, the temporary folder."""
    import tempfile

    spare = f"{path.stem}.saved{path.suffix}"
    yield path.with_name(spare)
    yield Path.cwd() / spare
    yield Path(tempfile.gettempdir()) / spare


@dataclass
class Outputs:
    """The output files of one command: written, announced, and saved elsewhere on failure.

    Parameters
    ----------
    lang : str
        A catalogue language.
    notes : text stream, optional
        Where ``written: PATH`` goes (default standard error, so standard output keeps only
        the result).

    Attributes
    ----------
    written : list of Path
        Every file written (where it really went).
    failures : list of Message
        One per output that did not go where it was asked; :meth:`text` joins them.
    """

    lang: str = "en"
    notes: TextIO | None = None
    written: list[Path] = field(default_factory=list)
    failures: list[Message] = field(default_factory=list)

    def announce(self, path: str | os.PathLike[str]) -> None:
        """Print the one ``written: PATH`` line of a file written."""
        self.written.append(Path(path))
        print(render("cli.written", self.lang, path=str(path)),
              file=self.notes or sys.stderr)

    def write(self, path: str | os.PathLike[str], writer: Callable[[Path], T]) -> T | None:
        """Write one output with ``writer(path)``; on failure save it elsewhere.

        Parameters
        ----------
        path : path-like
            The requested file, or folder.
        writer : callable
            Writes the output at the path it is given (it may be called again with another);
            when it returns a list of paths (the files it wrote in a folder), each is
            announced, else the path itself.

        Returns
        -------
        object or None
            What ``writer`` returned, None when no place took the output.
        """
        target = Path(path)
        try:
            value = writer(target)
        except OSError as exc:
            return self._save_elsewhere(target, writer, exc)
        self._announce_all(target, value)
        return value

    def _announce_all(self, target: Path, value: object) -> None:
        files = value if isinstance(value, list) and all(isinstance(p, Path) for p in value) \
            else [target]
        for file in files:
            self.announce(file)

    def write_text(self, path: str | os.PathLike[str], text: str) -> None:
        """Write a text output atomically (to standard output when ``path`` is
        :data:`STDOUT`); when no file takes it, print it instead."""
        from assur.io.files import atomic_write_text

        if str(path) == STDOUT:
            sys.stdout.write(text if text.endswith("\n") else text + "\n")
            return
        before = len(self.failures)
        self.write(path, lambda target: atomic_write_text(target, text))
        if len(self.failures) > before and self.failures[-1].code == "cli.output.lost":
            self.failures[-1] = Message("cli.output.printed", self.failures[-1].data)
            sys.stdout.write(text if text.endswith("\n") else text + "\n")

    def _save_elsewhere(self, target: Path, writer: Callable[[Path], T],
                        error: OSError) -> T | None:
        data = {"path": str(target), "reason": error.strerror or str(error)}
        for spare in _fallbacks(target):
            try:
                value = writer(spare)
            except OSError:
                continue
            self._announce_all(spare, value)
            self.failures.append(Message("cli.output.saved_elsewhere", {**data,
                                                                        "spare": str(spare)}))
            return value
        self.failures.append(Message("cli.output.lost", data))
        return None

    def text(self) -> str:
        """The failures as lines in the language of the outputs."""
        return "\n".join(m.text(self.lang) for m in self.failures)


def outputs_of(args: argparse.Namespace) -> Outputs:
    """The :class:`Outputs` of a command's run (made on first use, in the run's language).

    The command line makes it before the run and reports its failures after; a command
    called on its own gets one here.
    """
    found = getattr(args, "outputs", None)
    if not isinstance(found, Outputs):
        found = args.outputs = Outputs(getattr(args, "lang", "en"))
    return found
