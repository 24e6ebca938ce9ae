"""Shipped tables changed once where YAML is fragile end either read or in one clean
:class:`~assur.errors.TableError`: its sentences rendered in both languages, no parser words
in Russian, at most one caret per problem."""

from __future__ import annotations

import random
from pathlib import Path

from assur.errors import TableError
from assur.io.reader import TableReader

ROOT = Path(__file__).resolve().parent.parent
_EDITS = ("tab", "drop", "twice", "comma")
PARSER_WORDS = ("expected", "found", "while", "token", "scalar")


def _mutant(text: str, rng: random.Random) -> str:
    """``text`` changed once: a tab put in an indentation, a bracket, quote, colon or comma
    dropped, a line written twice, or a decimal point made a comma."""
    lines = text.splitlines(keepends=True)
    edit = rng.choice(_EDITS)
    if edit == "tab":
        row = rng.randrange(len(lines))
        lines[row] = "\t" + lines[row].lstrip(" ")
        return "".join(lines)
    if edit == "twice":
        row = rng.randrange(len(lines))
        return "".join(lines[:row + 1] + lines[row:])
    marks = [i for i, ch in enumerate(text) if ch in ("[]{}\"':," if edit == "drop" else ".")]
    if not marks:
        return text
    spot = rng.choice(marks)
    return text[:spot] + ("" if edit == "drop" else ",") + text[spot + 1:]


def test_mutated_tables_end_in_a_clean_table_error(tmp_path: Path) -> None:
    rng = random.Random(20251)
    sources = sorted((ROOT / "input_tables").rglob("*.yaml"))
    refused = 0
    for n in range(300):
        table = tmp_path / f"m{n}.yaml"
        table.write_text(_mutant(rng.choice(sources).read_text(encoding="utf-8"), rng),
                         encoding="utf-8")
        try:
            TableReader.from_path(table)
        except TableError as exc:
            refused += 1
            for lang in ("en", "ru"):
                shown = exc.text(lang).splitlines()
                assert str(table) in shown[0]
                assert sum(row.strip() == "^" for row in shown) <= len(exc.issues)
                assert not any(issue.message.code in issue.text(lang) for issue in exc.issues)
            sentences = [issue.text("ru").splitlines()[0] for issue in exc.issues]
            assert not any(word in line for word in PARSER_WORDS for line in sentences), \
                sentences  # the lines shown under a sentence are the user's
    assert refused > 100  # the edits do break tables
