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
import re
import stat
from collections.abc import Callable, Iterable, Iterator
from itertools import pairwise
from pathlib import Path
from typing import TYPE_CHECKING, Any

import yaml

from assur.errors import Issue, TableError
from assur.text import Message

__all__ = [
    "LARGEST",
    "MAX_BYTES",
    "MAX_DEPTH",
    "MISSING",
    "SMALLEST",
    "TABLE_KINDS",
    "Node",
    "TableReader",
    "WrittenList",
    "describe",
    "is_number",
    "latin_form",
    "lookalike_letters",
    "normalise_id",
    "number_problem",
    "positive",
    "radian_look",
    "table_kind",
    "with_commas",
]

#: Largest table file read (bytes); a bigger file is refused before it is parsed.
MAX_BYTES = 1_000_000
#: Deepest nesting of lists and mappings in a table; deeper is refused before parsing.
MAX_DEPTH = 32
#: Magnitude of the largest number a table may hold (mm, degrees, weights, counts).
LARGEST = 1e9
#: The smallest size (length, mass, tolerance) a table may hold.
SMALLEST = 1e-12

#: The kinds of table the program reads: name → (the command that reads it, the top-level
#: keys that only a table of that kind has).  The first kind whose keys a file has is its
#: kind; ``table.kind.<name>`` in the catalogue names it.
TABLE_KINDS: dict[str, tuple[str, frozenset[str]]] = {
    "problem": ("assur synthesize FILE",
                frozenset({"control_points", "parameters", "allowable", "search"})),
    "tracker": ("assur case tracker --table FILE", frozenset({"design_task"})),
    "impact": ("assur case impact --table FILE",
               frozenset({"lengths_mm", "masses_kg", "inertias_kg_mm2", "clearance_mm",
                          "omega4_rad_s"})),
    "fourbar_velocity_ratio": ("assur case fourbar-velocity-ratio --table FILE",
                               frozenset({"fourbar_velocity_ratio"})),
    "chain": ("assur check FILE, assur analyze FILE",
              frozenset({"mechanism", "structure_identification"})),
}

#: Cyrillic letters drawn like Latin ones → the Latin letter.
_LOOK_ALIKES = dict(zip(
    "аеорсухіјѕАВЕКМНОРСТХІЈЅ",  # letters, not text
    "aeopcyxijsABEKMHOPCTXIJS"))
_CYRILLIC = re.compile("[\u0400-\u04ff]")
_LATIN = re.compile("[A-Za-z]")
_RUSSIAN = re.compile("[А-яЁё]{2}")  # letters, not text
_DECIMAL_COMMA = re.compile(r"\s*[-+]?\d+,\d+\s*")


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
    and (not isinstance(v, float) or math.isfinite(v)),
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

    A text written with Cyrillic letters that look like Latin ones, and a number written with
    a decimal comma, are named as such.

    >>> [describe(v).text("en") for v in ("abc", None, [1, 2], 2.5)]
    ["'abc' (a text)", 'nothing (null)', 'a list of 2 items', '2.5']
    >>> describe([1, 2]).text("ru")
    'список из 2 элементов'
    >>> describe("Р").text("en")
    "'Р' (a text typed with Cyrillic letters that look like Latin ones: Р)"
    >>> describe("90,27").text("en")
    "'90,27' (a number written with a decimal comma; write 90.27)"
    """
    if value is None:
        return Message("value.null")
    if isinstance(value, bool):
        return Message("value.bool", {"value": value})
    if isinstance(value, (int, float)):
        return Message("value.number", {"value": value})
    if isinstance(value, str):
        if _DECIMAL_COMMA.fullmatch(value):
            return Message("value.decimal_comma", {"value": value,
                                                   "fixed": value.strip().replace(",", ".")})
        letters = lookalike_letters(value)
        if letters:
            return Message("value.text_lookalike", {"value": value, "letters": letters})
        return Message("value.text", {"value": value})
    if isinstance(value, list):
        listed = Message("value.list", {"n": len(value)})
        if isinstance(value, WrittenList) and value.commas:
            return Message("value.list_decimal_comma", {"list": listed, **value.comma()})
        return listed
    if isinstance(value, dict):
        return Message("value.mapping")
    return Message("value.other", {"type": type(value).__name__})


def with_commas(value: Any) -> Any:
    """``value`` as a message shows it as written: itself, or, for a list that hides a number
    with a decimal comma (a :class:`WrittenList`), the list with the comma named.

    >>> with_commas(_load("a: [36,5, 30, 50]", "t.yaml")["a"]).text("en")
    '[36, 5, 30, 50] (decimal comma? write 36.5 for 36,5)'
    >>> with_commas([1, 2])
    [1, 2]
    """
    if isinstance(value, WrittenList) and value.commas:
        return Message("value.shown_decimal_comma", {"value": str(list(value)),
                                                     **value.comma()})
    return value


#: Angles in radians that an angle in degrees is seldom written as, to three decimals → the
#: multiple of π/2 they are (π/2, π, 3π/2, 2π).
_RADIAN_LOOKS = {round(k * math.pi / 2, 3): k for k in (1, 2, 3, 4)}


def radian_look(value: float) -> Message | None:
    """The warning for an angle in degrees that looks written in radians: π/2, π, 3π/2 or 2π
    to three decimals (None when it does not).

    >>> radian_look(3.1416).text("en")
    '3.1416 looks like an angle in radians (π); angles are in degrees: did you mean 180?'
    >>> radian_look(3.0) is None, radian_look(90) is None
    (True, True)
    """
    k = _RADIAN_LOOKS.get(round(abs(value), 3))
    if k is None:
        return None
    return Message("table.warn_radian", {"value": value, "pi": Message(f"value.pi_{k}"),
                                         "degrees": round(math.degrees(value), 2)})


def lookalike_letters(text: str) -> str:
    """The Cyrillic letters of ``text`` that look like Latin ones, when the text is meant to
    be Latin: it mixes them with Latin letters, or it has no other Cyrillic letter.

    >>> lookalike_letters("pаirs"), lookalike_letters("Р"), lookalike_letters("шар")
    ('а', 'Р', '')
    """
    found = "".join(dict.fromkeys(ch for ch in text if ch in _LOOK_ALIKES))
    if not found:
        return ""
    others = [ch for ch in _CYRILLIC.findall(text) if ch not in _LOOK_ALIKES]
    return found if _LATIN.search(text) or not others else ""


def latin_form(text: str) -> str:
    """``text`` with its Cyrillic letters that look like Latin ones made Latin.

    >>> latin_form("pаirs"), latin_form("Р")
    ('pairs', 'P')
    """
    return "".join(_LOOK_ALIKES.get(ch, ch) for ch in text)


def is_number(value: Any) -> bool:
    """Whether ``value`` is a number a table may hold: finite and at most :data:`LARGEST` in
    magnitude (a size must also pass :func:`positive`).

    >>> [is_number(v) for v in (0, 2.5, -40, 1e308, 5e-324, float("nan"), True, "1")]
    [True, True, True, False, True, False, False, False]
    """
    return number_problem(value) is None


def number_problem(value: Any) -> Message | None:
    """What is wrong with ``value`` as a number of a table (None if nothing): the catalogue
    message of the expected number, for a field read outside :meth:`Node.get`."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return Message("value.kind.number")
    if isinstance(value, float) and not math.isfinite(value):
        return Message("value.kind.number")
    if abs(value) > LARGEST:
        return Message("rule.number_size", {"low": SMALLEST, "high": LARGEST})
    return None


def positive(value: float) -> Message | None:
    """The rule of a size (a length, a mass, a tolerance): at least :data:`SMALLEST`, so that
    a value such as 5e-324 is not taken for a size.

    >>> positive(2.5) is None, positive(-1).text("en"), positive(5e-324).text("en")
    (True, 'must be positive', 'must be positive, at least 1e-12')
    """
    if value >= SMALLEST:
        return None
    return Message("rule.positive_size", {"low": SMALLEST}) if value > 0 else \
        Message("rule.positive")


def table_kind(data: Any) -> str | None:
    """The kind of table ``data`` is (a name of :data:`TABLE_KINDS`), None if none fits.

    >>> table_kind({"design_task": {}}), table_kind({"mechanism": {}}), table_kind([1])
    ('tracker', 'chain', None)
    """
    if not isinstance(data, dict):
        return None
    keys = {key for key in data if isinstance(key, str)}
    return next((name for name, (_, marks) in TABLE_KINDS.items() if keys & marks), None)


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
        #: Things that look wrong but may be meant (an angle that looks like radians): they
        #: do not refuse the table and are shown beside its results.
        self.warnings: list[Issue] = []

    @classmethod
    def from_path(cls, path: str | os.PathLike[str], *, kind: str | None = None
                  ) -> TableReader:
        """Read and parse a YAML table file.

        The file is refused before parsing when it is not a regular file, larger than
        :data:`MAX_BYTES`, not UTF-8 text, or nested deeper than :data:`MAX_DEPTH`.

        Parameters
        ----------
        path : path-like
            The file.
        kind : str, optional
            The kind of table the caller reads (a name of :data:`TABLE_KINDS`): a file of
            another kind is refused with the command that reads it.

        Raises
        ------
        TableError
            At once, with the one problem that stops the file from being read.
        """
        path = Path(path)
        source = str(path)
        try:
            message = _file_problem(path)
            if message is None:
                with path.open("rb") as stream:
                    raw = stream.read(MAX_BYTES + 1)
                message = _text_problem(raw)
        except OSError as exc:
            message = Message("table.file_unreadable", {"error": exc.strerror or str(exc)})
        if message is None:
            text = raw.decode("utf-8-sig")
            try:
                message = _depth_problem(text)
                if message is None:
                    reader = cls(_load(text, source), source)
                    if kind is not None:
                        reader.expect(kind)
                    return reader
            except yaml.YAMLError as exc:
                message = _python_problem(text) or _yaml_problem(exc, text)
        raise TableError(source, [Issue("", message)])

    @classmethod
    def from_data(cls, data: Any, source: str = "<data>") -> TableReader:
        """Wrap data that is already parsed (a dict from Python code or a test)."""
        return cls(data, source)

    def expect(self, kind: str) -> None:
        """Refuse, at once, a table of another kind than ``kind`` (a name of
        :data:`TABLE_KINDS`), naming the command that reads it.

        >>> TableReader.from_data({"design_task": {}}, "t.yaml").expect("chain")
        Traceback (most recent call last):
        ...
        assur.errors.TableError: 1 problem in t.yaml:
          - this is the design task of the tracker case, not a mechanism table; \
run it with: assur case tracker --table FILE
        """
        found = table_kind(self.data)
        if found is not None and found != kind:
            raise TableError(self.source, [Issue("", Message("table.wrong_command", {
                "found": Message(f"table.kind.{found}"), "expected": Message(f"table.kind.{kind}"),
                "command": TABLE_KINDS[found][0]}))])

    def problem(self, location: str, code: str, /, **data: Any) -> None:
        """Record one problem: the catalogue code of its sentence and the values it shows.

        >>> reader = TableReader.from_data({}, source="demo.yaml")
        >>> reader.problem("links[2]", "lang.unknown", found="de", known="en")
        >>> reader.issues[0].text("en")
        "links[2]: no catalogue for language 'de'; the languages are en"
        """
        self.issues.append(Issue(location, Message(code, data)))

    def warn(self, location: str, code: str, /, **data: Any) -> None:
        """Record one warning: like :meth:`problem`, but the table is still read.

        >>> reader = TableReader.from_data({}, source="demo.yaml")
        >>> reader.warn("geometry 'B'", "lang.unknown", found="de", known="en")
        >>> reader.issues, len(reader.warnings)
        ([], 1)
        """
        self.warnings.append(Issue(location, Message(code, data)))

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
        #: Keys reported already (misspelt: the allowed key meant → the key as written; or
        #: swapped with another): such a key is not reported again, and reads as
        #: :data:`MISSING`.
        self.misspelt: dict[str, Any] = {}
        if allowed is not None:
            allowed = list(allowed)
            for key, value in mapping.items():
                if key not in allowed:
                    self._unknown(key, value, allowed)

    def _unknown(self, key: Any, value: Any, allowed: list[str]) -> None:
        """Report a key that is not allowed, naming the key meant when it is clear."""
        hint = difflib.get_close_matches(str(key), allowed, n=1, cutoff=0.6)
        letters = lookalike_letters(key) if isinstance(key, str) else ""
        if letters and latin_form(key) in allowed:
            self.reader.problem(self.location, "table.unknown_key_lookalike", key=key,
                                letters=letters, hint=latin_form(key))
            meant = latin_form(key)
        elif isinstance(key, int) and value is None:
            self.reader.problem(self.location, "table.decimal_comma_key", key=key)
            return
        elif hint:
            self.reader.problem(self.location, "table.unknown_key_hint", key=key, hint=hint[0])
            meant = hint[0]
        else:
            self.reader.problem(self.location, "table.unknown_key", key=key,
                                keys=", ".join(repr(k) for k in allowed))
            return
        if meant not in self.mapping:
            self.misspelt.setdefault(meant, key)

    def swapped(self, fits: dict[str, Callable[[Any], bool]]) -> None:
        """Report two fields whose values look swapped, once, as such: the value of one does
        not fit it but fits the other, whose value fits the first.  Both then read as
        :data:`MISSING`, without a message of their own.

        Parameters
        ----------
        fits : dict
            Field → whether a value fits it (a quick test of its kind and options).

        >>> reader = TableReader.from_data({}, "t.yaml")
        >>> row = Node(reader, "pairs[0]", {"type": [1, 2], "links": "R"}, None)
        >>> row.swapped({"type": lambda v: v in ("R", "P"),
        ...              "links": lambda v: isinstance(v, list)})
        >>> reader.issues[0].text("en"), row.get("type"), row.get("links")
        ("pairs[0]: the values of 'type' and 'links' look swapped", MISSING, MISSING)
        """
        keys = [key for key in fits if key in self.mapping and key not in self.misspelt]
        for a in keys:
            value_a = self.mapping[a]
            if fits[a](value_a):
                continue
            for b in keys:
                value_b = self.mapping[b]
                if b != a and b not in self.misspelt and fits[a](value_b) and \
                        fits[b](value_a):
                    self.reader.problem(self.location, "table.swapped", a=a, b=b)
                    self.misspelt[a], self.misspelt[b] = b, a
                    break

    def _where(self, key: str) -> str:
        return f"{self.location} {key!r}".strip() if self.location else repr(key)

    def has(self, key: str) -> bool:
        """Whether the key is present (even with a null value)."""
        return key in self.mapping

    def given(self, key: str) -> bool:
        """Whether the key is present, or written misspelt (reported already): a check that
        a key is there uses this, so that a misspelt key is not also reported missing."""
        return key in self.mapping or key in self.misspelt

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
            The value, or :data:`MISSING` when it is absent or invalid (already recorded),
            or written misspelt (reported as such, not again as missing).
        """
        if key in self.misspelt:
            return MISSING
        if key not in self.mapping:
            if required:
                self.reader.problem(self._where(key), "table.missing",
                                    expected=Message(f"value.kind.{kind}"))
                return MISSING
            return default
        value = self.mapping[key]
        if value is None and nullable:
            return None
        written = value
        if kind == "number" and isinstance(value, str):
            value = _parse_number(value)
        if not _KINDS[kind](value):
            self.reader.problem(self._where(key), "table.wrong_kind",
                                expected=Message(f"value.kind.{kind}"), found=describe(written))
            return MISSING
        if kind in ("number", "int") and number_problem(value) is not None:
            self.reader.problem(self._where(key), "table.rule_broken",
                                rule=number_problem(value), found=describe(value))
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
        if _hashable(value) and value in options:
            return value
        if isinstance(value, str) and latin_form(value) in options and lookalike_letters(value):
            letters = lookalike_letters(value)
            self.reader.problem(self._where(key), "table.option_lookalike", value=value,
                                letters=letters, hint=latin_form(value))
        else:
            self.reader.problem(self._where(key), "table.not_an_option",
                                options=", ".join(repr(o) for o in options), found=describe(value))
        return MISSING

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


def _hashable(value: Any) -> bool:
    return not isinstance(value, (list, dict, set))


def _file_problem(path: Path) -> Message | None:
    """Why ``path`` cannot be a table file (None if it can): missing, a folder, not a regular
    file, or too large."""
    try:
        info = path.stat()
    except FileNotFoundError:
        return Message("table.file_missing")
    if stat.S_ISDIR(info.st_mode):
        return Message("table.file_is_folder")
    if not stat.S_ISREG(info.st_mode):
        return Message("table.file_special")
    if info.st_size > MAX_BYTES:
        return Message("table.too_large", {"limit": MAX_BYTES, "found": info.st_size})
    return None


def _text_problem(raw: bytes) -> Message | None:
    """Why the bytes of a file are not a table's text (None if they are): too many, or not
    UTF-8 (the likely encoding is named when the bytes decode as Windows-1251 Cyrillic)."""
    if len(raw) > MAX_BYTES:
        return Message("table.too_large", {"limit": MAX_BYTES, "found": len(raw)})
    try:
        raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
            return Message("table.encoding_named", {"line": line, "encoding": "UTF-16"})
        if _RUSSIAN.search(raw.decode("cp1251", errors="replace")):
            return Message("table.encoding_named", {"line": line, "encoding": "Windows-1251"})
        return Message("table.encoding", {"line": line, "byte": f"0x{raw[exc.start]:02X}"})
    return None


_OPENING = (yaml.BlockMappingStartToken, yaml.BlockSequenceStartToken,
            yaml.FlowMappingStartToken, yaml.FlowSequenceStartToken)
_CLOSING = (yaml.BlockEndToken, yaml.FlowMappingEndToken, yaml.FlowSequenceEndToken)


#: PyYAML's safe loader, through libyaml where PyYAML was built with it (the same tokens, nodes
#: and types, several times faster than the pure-Python scanner).
if TYPE_CHECKING:  # the two loaders have one interface
    _LOADER = yaml.SafeLoader
else:
    _LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def _depth_problem(text: str, loader: Any = _LOADER) -> Message | None:
    """Nesting deeper than :data:`MAX_DEPTH`, found by the token scanner (which, unlike the
    parser, does not recurse), before the text is parsed."""
    depth = 0
    for token in yaml.scan(text, Loader=loader):
        if isinstance(token, _OPENING):
            depth += 1
            if depth > MAX_DEPTH:
                return Message("table.too_deep", {"limit": MAX_DEPTH,
                                                  "line": token.start_mark.line + 1})
        elif isinstance(token, _CLOSING):
            depth -= 1
    return None


class WrittenList(list[Any]):
    """A list of a table as it was written: a flow list (``[0, 49,5]``) remembers the pairs of
    numbers written with a comma and no space between them (``49,5``), which YAML reads as two
    entries and which are most likely one number with a decimal comma.  The description of a
    list of the wrong length names them (:func:`describe`).

    >>> describe(_load("point: [0, 49,5]", "t.yaml")["point"]).text("en")
    'a list of 3 items; decimal comma? write 49.5 for 49,5'
    """

    commas: tuple[str, ...] = ()

    def comma(self) -> dict[str, str]:
        """The first number with a decimal comma as written, and as it should be."""
        return {"written": self.commas[0], "fixed": self.commas[0].replace(",", ".")}


class _Loader(_LOADER):
    """The safe loader of the tables, which also notes, as it builds the data, a key written
    twice in one mapping (YAML keeps the last in silence) and a value written with a decimal
    comma: ``l_1: 40,5`` (read as a text) and, inside a flow mapping, ``{l_1: 40,5}`` (read as
    ``l_1: 40`` and a key ``5``)."""

    def __init__(self, text: str) -> None:
        super().__init__(text)
        self.text = text
        self.found: list[tuple[int, int, Message]] = []

    def construct_mapping(self, node: Any, deep: bool = False) -> Any:
        """The mapping of ``node``, after noting its repeated keys and decimal commas."""
        seen: dict[Any, Any] = {}
        previous: Any = None
        for key_node, value_node in node.value:
            key = self.construct_object(key_node, deep=True)
            if _hashable(key):
                first = seen.setdefault(key, key_node)
                if first is not key_node:
                    line = first.start_mark.line
                    self._note(key_node, "table.yaml_duplicate_key" if line <
                               key_node.start_mark.line else "table.yaml_duplicate_key_row",
                               key=str(key), first=line + 1)
            if node.flow_style and previous is not None and \
                    _comma_split(previous[1], key_node) and _implicit_null(value_node):
                written = f"{previous[1].value},{key_node.value}"
                self._note(previous[1], "table.yaml_decimal_comma_key",
                           key=str(self.construct_object(previous[0], deep=True)),
                           written=written, fixed=written.replace(",", "."),
                           whole=previous[1].value, part=key_node.value)
            if _comma_number(value_node):
                self._note(value_node, "table.yaml_decimal_comma", key=str(key),
                           written=value_node.value,
                           fixed=value_node.value.strip().replace(",", "."))
            previous = (key_node, value_node)
        return super().construct_mapping(node, deep=deep)

    def construct_flow_list(self, node: Any) -> Iterator[list[Any]]:
        """A list, kept as a :class:`WrittenList` when it holds a number with a decimal
        comma that YAML read as two (``[0, 49,5]``); an item ``- 49,5`` is noted."""
        items = node.value
        for item in items:
            if _comma_number(item):
                self._note(item, "table.yaml_decimal_comma_item", written=item.value,
                           fixed=item.value.strip().replace(",", "."))
        commas = tuple(f"{a.value},{b.value}" for a, b in pairwise(items)
                       if node.flow_style and _comma_split(a, b))
        data: list[Any] = []
        if commas:
            data = written = WrittenList()
            written.commas = commas
        yield data
        data.extend(self.construct_sequence(node))

    def _note(self, node: Any, code: str, **data: Any) -> None:
        mark = node.start_mark
        self.found.append((mark.line, mark.column, Message(code, {
            "line": mark.line + 1, "column": mark.column + 1,
            "excerpt": _excerpt(self.text, mark.line, mark.column), **data})))


_Loader.add_constructor("tag:yaml.org,2002:seq", _Loader.construct_flow_list)

_INTEGER = re.compile(r"[-+]?\d+")
_DIGITS = re.compile(r"\d+")


def _comma_split(a: Any, b: Any) -> bool:
    """Whether nodes ``a`` and ``b`` are two plain integers written ``49,5``: a comma and no
    space between them (a plain scalar's style is None, or '' from libyaml)."""
    return (isinstance(a, yaml.ScalarNode) and isinstance(b, yaml.ScalarNode)
            and not a.style and not b.style
            and _INTEGER.fullmatch(a.value) is not None and _DIGITS.fullmatch(b.value) is not None
            and a.end_mark.index + 1 == b.start_mark.index)


def _comma_number(node: Any) -> bool:
    """Whether ``node`` is a number with a decimal comma written without quotes
    (``l_1: 40,5``), which YAML reads as a text."""
    return (isinstance(node, yaml.ScalarNode) and not node.style
            and node.tag == "tag:yaml.org,2002:str"
            and _DECIMAL_COMMA.fullmatch(node.value) is not None)


def _implicit_null(node: Any) -> bool:
    """Whether ``node`` is a value not written at all (a key without ``:``)."""
    return isinstance(node, yaml.ScalarNode) and node.value == "" and not node.style


def _load(text: str, source: str) -> Any:
    """The data of a table's YAML text; a key written twice or a decimal comma inside a flow
    mapping is refused with every place where it occurs.

    >>> _load("a: 1\\nb: 2\\na: 3\\n", "t.yaml")
    Traceback (most recent call last):
    ...
    assur.errors.TableError: 1 problem in t.yaml:
      - line 3, column 1: the key 'a' is written twice, on lines 1 and 3; YAML would keep \
the last in silence: keep one
        a: 3
        ^
    """
    loader = _Loader(text)
    try:
        data = loader.get_single_data()
    finally:
        loader.dispose()
    if loader.found:
        raise TableError(source, [Issue("", message)
                                  for *_, message in sorted(loader.found, key=lambda f: f[:2])])
    return data


def _python_problem(text: str) -> Message | None:
    """The problem of a text that libyaml refused, in the words of PyYAML's own parser (the
    same position, a plainer sentence); its depth is checked first, so it never recurses deep.
    """
    try:
        depth = _depth_problem(text, yaml.SafeLoader)
        if depth is not None:
            return depth
        yaml.safe_load(text)
    except yaml.YAMLError as exc:
        return _yaml_problem(exc, text)
    return None


def _excerpt(text: str, line: int, column: int) -> str:
    """The line ``line`` (from 0) of ``text`` with a caret under ``column``, indented to sit
    under a problem of :class:`~assur.errors.TableError` (a tab is shown as a space, so that
    the caret stays under its spot)."""
    lines = text.splitlines()
    if not 0 <= line < len(lines):
        return ""
    shown = lines[line].replace("\t", " ").rstrip()
    return f"\n    {shown}\n    {' ' * min(column, len(shown))}^"


#: Brackets of YAML's flow collections: opening → closing.
_BRACKETS = {"[": "]", "{": "}"}


def _open_bracket(text: str, end: int) -> int | None:
    """Where the innermost bracket still open at ``end`` of ``text`` was opened (None when
    none is), skipping quoted texts and comments: the place to name when the parser stops
    inside a flow collection without saying which.

    >>> _open_bracket("a: {b: [1, 2], c: 3\\n- d", 22)
    3
    """
    stack: list[int] = []
    quote = ""
    index = 0
    while index < min(end, len(text)):
        ch = text[index]
        if quote:
            if ch == quote:
                quote = ""
        elif ch in "\"'" and (index == 0 or text[index - 1] in " \t[{,:\n"):
            quote = ch
        elif ch == "#" and (index == 0 or text[index - 1] in " \t\n"):
            newline = text.find("\n", index)
            index = len(text) if newline == -1 else newline
            continue
        elif ch in _BRACKETS:
            stack.append(index)
        elif ch in "]}" and stack:
            stack.pop()
        index += 1
    return stack[-1] if stack else None


def _yaml_problem(exc: yaml.YAMLError, text: str) -> Message:
    """The problem of a text that is not YAML, in plain words: the spot (line, column, the line
    itself with a caret under the spot) and what to do; an unclosed bracket or quote is shown
    where it was opened."""
    mark = getattr(exc, "problem_mark", None)
    if mark is None:
        return Message("table.not_yaml")
    problem = str(getattr(exc, "problem", None) or "")
    context = str(getattr(exc, "context", None) or "")
    opened = getattr(exc, "context_mark", None)
    spot = {"line": mark.line + 1, "column": mark.column + 1,
            "excerpt": _excerpt(text, mark.line, mark.column)}
    if "'\\t'" in problem or (mark.index < len(text) and text[mark.index] == "\t"):
        return Message("table.yaml_tab", spot)
    if context.startswith("while parsing a flow"):
        start = opened.index if opened is not None and opened.index < len(text) and \
            text[opened.index] in _BRACKETS else _open_bracket(text, mark.index)
        if start is not None:
            line = text.count("\n", 0, start)
            column = start - (text.rfind("\n", 0, start) + 1)
            bracket = text[start]
            return Message("table.yaml_unclosed", {
                "line": line + 1, "column": column + 1,
                "excerpt": _excerpt(text, line, column), "bracket": bracket,
                "closing": _BRACKETS[bracket], "at_line": mark.line + 1,
                "at_column": mark.column + 1})
    if opened is not None and context.startswith("while scanning a quoted"):
        return Message("table.yaml_quote", {
            "line": opened.line + 1, "column": opened.column + 1,
            "excerpt": _excerpt(text, opened.line, opened.column)})
    if problem.startswith("mapping values are not allowed"):
        return Message("table.yaml_colon", spot)
    if problem.startswith("could not find expected ':'") and opened is not None:
        return Message("table.yaml_no_colon", {
            "line": opened.line + 1, "column": opened.column + 1,
            "excerpt": _excerpt(text, opened.line, opened.column)})
    if problem.startswith("expected <block end>") or context.startswith("while parsing a block"):
        return Message("table.yaml_indent", spot)
    if "that cannot start any token" in problem and mark.index < len(text):
        return Message("table.yaml_character", {**spot, "character": text[mark.index]})
    if "unhashable key" in problem:
        return Message("table.yaml_key", spot)
    if problem.startswith("could not determine a constructor"):
        return Message("table.yaml_tag", spot)
    if problem.startswith("found undefined alias"):
        return Message("table.yaml_alias", spot)
    return Message("table.yaml_syntax", spot)
