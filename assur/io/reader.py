"""Reading user tables: YAML loading and field checks that collect every problem at once.

Every table of the program (chains, identification tables, synthesis problems, the input
tables of the built-in cases) is read through :class:`TableReader`, so that all of them
report problems the same way: file, table, row and field, what was expected and what was
found, every problem in one :class:`~assur.errors.TableError`.

Examples
--------
>>> reader = TableReader.from_data({"links": [0, 1], "framee": 0}, source="demo.yaml")
>>> top = reader.root(allowed={"links", "frame"})
>>> _ = top.get("links", kind="list")
>>> reader.issues[0].text("en")
"unknown key 'framee'; did you mean 'frame'?"
"""

from __future__ import annotations

import difflib
import math
import os
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

import yaml  # type: ignore[import-untyped]

from assur.errors import Issue, TableError
from assur.text import Message

__all__ = [
    "MISSING",
    "Node",
    "TableReader",
    "describe",
    "normalise_id",
]


class _Missing:
    """Marker for a value that was absent or invalid (the problem is already recorded)."""

    def __repr__(self) -> str:
        return "MISSING"

    def __bool__(self) -> bool:
        return False


MISSING: Any = _Missing()

#: Kind of a field → its test; ``value.kind.<kind>`` in the catalogue names the kind.
_KINDS: dict[str, Callable[[Any], bool]] = {
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool)
    and math.isfinite(v),
    "int": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "str": lambda v: isinstance(v, str),
    "id": lambda v: (isinstance(v, int) and not isinstance(v, bool))
    or (isinstance(v, str) and v.strip() != ""),
    "list": lambda v: isinstance(v, list),
    "mapping": lambda v: isinstance(v, dict),
    "bool": lambda v: isinstance(v, bool),
    "any": lambda v: True,
}


def describe(value: Any) -> Message:
    """Say briefly what a found value is, for error messages.

    >>> [describe(v).text("en") for v in ("abc", None, [1, 2], 2.5)]
    ["'abc' (a text)", 'nothing (null)', 'a list of 2 items', '2.5']
    >>> describe([1, 2]).text("ru")
    'список из 2 элементов'
    """
    if value is None:
        return Message("value.null")
    if isinstance(value, bool):
        return Message("value.bool", {"value": value})
    if isinstance(value, (int, float)):
        return Message("value.number", {"value": value})
    if isinstance(value, str):
        return Message("value.text", {"value": value})
    if isinstance(value, list):
        return Message("value.list", {"n": len(value)})
    if isinstance(value, dict):
        return Message("value.mapping")
    return Message("value.other", {"type": type(value).__name__})


def normalise_id(value: Any) -> Any:
    """Link and pair ids: integers stay integers, digit-only texts become integers.

    >>> normalise_id("7"), normalise_id(7), normalise_id("A")
    (7, 7, 'A')
    """
    if isinstance(value, str) and value.strip().isdigit():
        return int(value.strip())
    return value.strip() if isinstance(value, str) else value


class TableReader:
    """Collects the problems of one table file while its content is read.

    Parameters
    ----------
    data : object
        The parsed YAML document.
    source : str
        The file name used in every message.
    """

    def __init__(self, data: Any, source: str) -> None:
        self.data = data
        self.source = source
        self.issues: list[Issue] = []

    @classmethod
    def from_path(cls, path: str | os.PathLike[str]) -> TableReader:
        """Parse a YAML file; an unreadable file raises :class:`TableError` at once."""
        path = Path(path)
        source = str(path)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            message = Message("table.file_missing")
        except IsADirectoryError:
            message = Message("table.file_is_folder")
        except (OSError, UnicodeDecodeError) as exc:
            message = Message("table.file_unreadable", {"error": str(exc)})
        else:
            try:
                return cls(yaml.safe_load(text), source)
            except yaml.YAMLError as exc:
                mark = getattr(exc, "problem_mark", None)
                problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
                message = (Message("table.not_yaml_at", {"line": mark.line + 1,
                                                         "column": mark.column + 1,
                                                         "problem": problem})
                           if mark else Message("table.not_yaml", {"problem": problem}))
        raise TableError(source, [Issue("", message)])

    @classmethod
    def from_data(cls, data: Any, source: str = "<data>") -> TableReader:
        """Wrap data that is already parsed (a dict from Python code or a test)."""
        return cls(data, source)

    def problem(self, location: str, code: str, /, **data: Any) -> None:
        """Record one problem: the catalogue code of its sentence and the values it shows.

        >>> reader = TableReader.from_data({}, source="demo.yaml")
        >>> reader.problem("links[2]", "lang.unknown", found="de", known="en")
        >>> reader.issues[0].text("en")
        "links[2]: no catalogue for language 'de'; the languages are en"
        """
        self.issues.append(Issue(location, Message(code, data)))

    def root(self, allowed: Iterable[str] | None = None, *, name: str = "") -> Node:
        """The top of the document, which must be a mapping."""
        if not isinstance(self.data, dict):
            self.problem(name, "table.top_not_mapping", found=describe(self.data))
            return Node(self, name, {}, allowed)
        return Node(self, name, self.data, allowed)

    def raise_if_any(self) -> None:
        """Raise one :class:`TableError` listing every recorded problem, if there are any."""
        if self.issues:
            raise TableError(self.source, self.issues)


class Node:
    """A mapping inside a table (the whole document, a table, or one row).

    Unknown keys are reported on construction with a did-you-mean suggestion.
    """

    def __init__(self, reader: TableReader, location: str, mapping: dict[str, Any],
                 allowed: Iterable[str] | None) -> None:
        self.reader = reader
        self.location = location
        self.mapping = mapping
        if allowed is not None:
            allowed = list(allowed)
            for key in mapping:
                if key not in allowed:
                    hint = difflib.get_close_matches(str(key), allowed, n=1, cutoff=0.6)
                    if hint:
                        reader.problem(location, "table.unknown_key_hint", key=key, hint=hint[0])
                    else:
                        reader.problem(location, "table.unknown_key", key=key,
                                       keys=", ".join(repr(k) for k in allowed))

    def _where(self, key: str) -> str:
        return f"{self.location} {key!r}".strip() if self.location else repr(key)

    def has(self, key: str) -> bool:
        """Whether the key is present (even with a null value)."""
        return key in self.mapping

    def get(self, key: str, *, kind: str = "any", required: bool = True, default: Any = MISSING,
            check: Callable[[Any], Message | None] | None = None,
            nullable: bool = False) -> Any:
        """Read one field.

        Parameters
        ----------
        key : str
            Field name.
        kind : {'number', 'int', 'str', 'id', 'list', 'mapping', 'bool', 'any'}
            Expected type.
        required : bool
            Whether a missing field is a problem (otherwise ``default`` is returned).
        default : object
            Value for an absent optional field.
        check : callable, optional
            Returns the rule the value breaks, as a catalogue message
            (``Message("rule.positive")``: "must be positive"), or None.
        nullable : bool
            Whether an explicit null is accepted (returned as None).

        Returns
        -------
        object
            The value, or :data:`MISSING` when it is absent or invalid (already recorded).
        """
        if key not in self.mapping:
            if required:
                self.reader.problem(self._where(key), "table.missing",
                                    expected=Message(f"value.kind.{kind}"))
                return MISSING
            return default
        value = self.mapping[key]
        if value is None and nullable:
            return None
        if kind == "number" and isinstance(value, str):
            value = _parse_number(value)
        if not _KINDS[kind](value):
            self.reader.problem(self._where(key), "table.wrong_kind",
                                expected=Message(f"value.kind.{kind}"), found=describe(value))
            return MISSING
        if kind == "id":
            value = normalise_id(value)
        if check is not None:
            rule = check(value)
            if rule is not None:
                self.reader.problem(self._where(key), "table.rule_broken", rule=rule,
                                    found=describe(value))
                return MISSING
        return value

    def choice(self, key: str, options: Iterable[Any], *, required: bool = True,
               default: Any = MISSING) -> Any:
        """Read a field that must be one of a few values."""
        options = list(options)
        value = self.get(key, required=required, default=default)
        if value is MISSING or (not required and value is default):
            return value
        if value not in options:
            self.reader.problem(self._where(key), "table.not_an_option",
                                options=", ".join(repr(o) for o in options), found=describe(value))
            return MISSING
        return value

    def child(self, key: str, allowed: Iterable[str] | None = None, *,
              required: bool = True) -> Node | None:
        """A nested mapping; None when absent (recorded if required) or not a mapping."""
        value = self.get(key, kind="mapping", required=required, default=None)
        if not isinstance(value, dict):
            return None
        return Node(self.reader, f"{self.location}.{key}".lstrip("."), value, allowed)

    def rows(self, key: str, allowed: Iterable[str] | None = None, *, required: bool = True,
             label: Callable[[dict[str, Any]], str | None] | None = None) -> Iterator[Node]:
        """The rows of a list-valued table; rows that are not mappings are recorded."""
        value = self.get(key, kind="list", required=required, default=[])
        if not isinstance(value, list):
            return
        table = f"{self.location}.{key}".lstrip(".") if self.location else key
        for index, row in enumerate(value):
            where = f"{table}[{index}]"
            if not isinstance(row, dict):
                self.reader.problem(where, "table.not_a_row", found=describe(row))
                continue
            name = label(row) if label else None
            if name:
                where = f"{where} ({name})"
            yield Node(self.reader, where, row, allowed)


def _parse_number(text: str) -> Any:
    try:
        return float(text)
    except ValueError:
        return text
