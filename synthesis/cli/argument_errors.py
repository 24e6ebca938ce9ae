"""The command line's own mistakes (a misspelt command, a missing table, an unknown option)
told in the user's language, with the nearest right word where there is one.

:mod:`argparse` words its errors in English; :func:`translated` recognises each of its
sentences and renders the same facts from the catalogue (``cli.error.*``).  A sentence it does
not recognise (a future Python's new wording) is shown as argparse wrote it, never lost.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable, Sequence

from assur.text import render

__all__ = ["translated"]

#: argparse's sentences (Python 3.10–3.13) → the catalogue code and the names of their fields.
_SENTENCES: tuple[tuple[re.Pattern[str], str], ...] = tuple(
    (re.compile(pattern), code) for pattern, code in (
        (r"invalid choice: (?P<value>.+?) \(choose from (?P<choices>.+)\)", "cli.error.choice"),
        (r"the following arguments are required: (?P<names>.+)", "cli.error.required"),
        (r"unrecognized arguments: (?P<names>.+)", "cli.error.unrecognized"),
        (r"expected one argument", "cli.error.one_value"),
        (r"expected at most one argument", "cli.error.one_value"),
        (r"expected at least one argument", "cli.error.some_values"),
        (r"expected (?P<n>\d+) arguments?", "cli.error.values"),
        (r"invalid (?P<kind>\w+) value: (?P<value>.+)", "cli.error.value"),
        (r"not allowed with argument (?P<name>.+)", "cli.error.not_with"),
        (r"one of the arguments (?P<names>.+) is required", "cli.error.one_of"),
        (r"ambiguous option: (?P<option>\S+) could match (?P<matches>.+)", "cli.error.ambiguous"),
    ))
_ARGUMENT = re.compile(r"argument (?P<name>[^:]+): (?P<message>.+)", re.DOTALL)


def _words(listed: str) -> list[str]:
    """The words of argparse's list ``'a', 'b'`` (quoted or not)."""
    return [word.strip().strip("'\"") for word in listed.split(",") if word.strip()]


def _nearest(word: str, known: Sequence[str]) -> str | None:
    close = difflib.get_close_matches(word, known, n=1, cutoff=0.6)
    return close[0] if close else None


def translated(message: str, lang: str, options: Callable[[], Sequence[str]]) -> str:
    """argparse's error ``message`` in ``lang``, with a suggestion for a misspelt word.

    Parameters
    ----------
    message : str
        The sentence :meth:`argparse.ArgumentParser.error` received.
    lang : str
        The language of the report.
    options : callable
        Returns the option strings of the parser (for the nearest known option).

    Returns
    -------
    str
        The sentence in ``lang``.

    Examples
    --------
    >>> print(translated("argument COMMAND: invalid choice: 'chek' (choose from 'check', "
    ...                  "'analyze')", "en", list))
    argument COMMAND: invalid choice 'chek' (one of: check, analyze); did you mean 'check'?
    >>> print(translated("unrecognized arguments: --jsn", "ru", lambda: ["--json"]))
    неизвестные аргументы: --jsn; возможно, имелось в виду '--json'?
    """
    argument = _ARGUMENT.fullmatch(message)
    core = argument["message"] if argument else message
    for pattern, code in _SENTENCES:
        found = pattern.fullmatch(core)
        if found is None:
            continue
        data: dict[str, object] = dict(found.groupdict())
        hint = None
        if code == "cli.error.choice":
            value, choices = str(data["value"]).strip("'\""), _words(str(data["choices"]))
            data = {"value": value, "choices": ", ".join(choices)}
            hint = _nearest(value, choices)
        elif code == "cli.error.unrecognized":
            hint = next((near for word in str(data["names"]).split() if word.startswith("-")
                         for near in [_nearest(word.split("=")[0], options())] if near), None)
        elif code == "cli.error.value" and data["kind"] in ("int", "float"):
            code = f"cli.error.value_{data['kind']}"
        elif "n" in data:
            data["n"] = int(str(data["n"]))
        text = render(code, lang, **data)
        if hint is not None:
            text += render("cli.error.did_you_mean", lang, word=hint)
        if argument:
            return render("cli.error.argument", lang, name=argument["name"], message=text)
        return text
    return message
