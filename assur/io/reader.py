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
>>> reader.issues[0].message
"unknown key 'framee'; did you mean 'frame'?"
"""

from __future__ import annotations

import difflib
import math
import os
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

import yaml

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

_KINDS: dict[str, tuple[str, Callable[[Any], bool]]] = {
    "number": ("a number", lambda v: isinstance(v, (int, float)) and not isinstance(v, bool)
               and math.isfinite(v)),
    "int": ("a whole number", lambda v: isinstance(v, int) and not isinstance(v, bool)),
    "str": ("a text", lambda v: isinstance(v, str)),
    "id": ("an id (a whole number or a text)",
           lambda v: (isinstance(v, int) and not isinstance(v, bool)) or
           (isinstance(v, str) and v.strip() != "")),
    "list": ("a list", lambda v: isinstance(v, list)),
    "mapping": ("a mapping (key: value)", lambda v: isinstance(v, dict)),
    "bool": ("true or false", lambda v: isinstance(v, bool)),
    "any": ("a value", lambda v: True),
}


_KINDS_RU = {
    "number": "число", "int": "целое число", "str": "текст",
    "id": "номер (целое число или текст)", "list": "список",
    "mapping": "словарь (ключ: значение)", "bool": "true или false", "any": "значение",
}


def describe(value: Any, lang: str = "en") -> str:
    """Say briefly what a found value is, for error messages.

    >>> describe("abc"), describe(None), describe([1, 2]), describe([1, 2], "ru")
    ("'abc' (a text)", 'nothing (null)', 'a list of 2 items', 'список из 2 элементов')
    """
    ru = lang == "ru"
    if value is None:
        return "пусто (null)" if ru else "nothing (null)"
    if isinstance(value, bool):
        return f"{value!r} (true/false)"
    if isinstance(value, (int, float)):
        return f"{value!r}"
    if isinstance(value, str):
        return f"{value!r} ({'текст' if ru else 'a text'})"
    if isinstance(value, list):
        if ru:
            return f"список из {len(value)} элементов"
        return f"a list of {len(value)} item{'s' if len(value) != 1 else ''}"
    if isinstance(value, dict):
        return "словарь" if ru else "a mapping"
    return type(value).__name__


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
            raise TableError(source, [Issue("", "the file does not exist",
                                            "такого файла нет")]) from None
        except IsADirectoryError:
            raise TableError(source, [Issue("", "this is a folder, not a table file",
                                            "это папка, а не файл таблицы")]) from None
        except (OSError, UnicodeDecodeError) as exc:
            raise TableError(source, [Issue("", f"the file cannot be read ({exc})",
                                            f"файл не читается ({exc})")]) from None
        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else ""
            problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
            raise TableError(source, [Issue(where, f"this is not valid YAML: {problem}",
                                            f"это не корректный YAML: {problem}")]) from None
        return cls(data, source)

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

    def add(self, location: str, message: str, message_ru: str = "") -> None:
        """Record one problem as English (and Russian) text; to be replaced by
        :meth:`problem` wherever a sentence has moved into the catalogue."""
        self.issues.append(Issue(location, message, message_ru))

    def root(self, allowed: Iterable[str] | None = None, *, name: str = "") -> Node:
        """The top of the document, which must be a mapping."""
        if not isinstance(self.data, dict):
            self.add(name, f"expected a mapping of tables at the top of the file; found "
                           f"{describe(self.data)}",
                     f"в начале файла ожидался словарь таблиц; найдено {describe(self.data, 'ru')}")
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
                    keys = ", ".join(repr(k) for k in allowed)
                    tail = f"; did you mean {hint[0]!r}?" if hint else f"; expected one of {keys}"
                    tail_ru = (f"; возможно, имелось в виду {hint[0]!r}?" if hint
                               else f"; допустимы: {keys}")
                    reader.add(location, f"unknown key {key!r}{tail}",
                               f"неизвестный ключ {key!r}{tail_ru}")

    def _where(self, key: str) -> str:
        return f"{self.location} {key!r}".strip() if self.location else repr(key)

    def has(self, key: str) -> bool:
        """Whether the key is present (even with a null value)."""
        return key in self.mapping

    def get(self, key: str, *, kind: str = "any", required: bool = True, default: Any = MISSING,
            check: Callable[[Any], str | tuple[str, str] | None] | None = None,
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
            Returns a text describing the rule broken ("must be positive"), or an
            (English, Russian) pair of such texts, or None.
        nullable : bool
            Whether an explicit null is accepted (returned as None).

        Returns
        -------
        object
            The value, or :data:`MISSING` when it is absent or invalid (already recorded).
        """
        if key not in self.mapping:
            if required:
                self.reader.add(self._where(key),
                                f"this field is missing; expected {_KINDS[kind][0]}",
                                f"поле отсутствует; ожидалось {_KINDS_RU[kind]}")
                return MISSING
            return default
        value = self.mapping[key]
        if value is None and nullable:
            return None
        label, test = _KINDS[kind]
        if kind == "number" and isinstance(value, str):
            value = _parse_number(value)
        if not test(value):
            self.reader.add(self._where(key), f"expected {label}; found {describe(value)}",
                            f"ожидалось {_KINDS_RU[kind]}; найдено {describe(value, 'ru')}")
            return MISSING
        if kind == "id":
            value = normalise_id(value)
        if check is not None:
            rule = check(value)
            if rule:
                rule_en, rule_ru = rule if isinstance(rule, tuple) else (rule, "")
                self.reader.add(self._where(key), f"{rule_en}; found {describe(value)}",
                                f"{rule_ru}; найдено {describe(value, 'ru')}" if rule_ru else "")
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
            options_text = ", ".join(repr(o) for o in options)
            self.reader.add(self._where(key),
                            f"expected one of {options_text}; found {describe(value)}",
                            f"ожидалось одно из: {options_text}; найдено {describe(value, 'ru')}")
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
                self.reader.add(where, f"expected a row (a mapping such as {{id: A, ...}}); "
                                       f"found {describe(row)}",
                                f"ожидалась строка таблицы (словарь вида {{id: A, ...}}); "
                                f"найдено {describe(row, 'ru')}")
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
