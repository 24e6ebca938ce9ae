"""One catalogue of every sentence a user reads, in every language the program speaks.

The catalogue is a set of gettext PO files, one per language, in ``assur/locale/``:
``en.po``, ``ru.po``, … Each entry's ``msgid`` is a stable code (``"table.unknown_key"``,
``"reason.rrr.too_far"``) and its ``msgstr`` the sentence, with named fields in
:meth:`str.format` syntax (``"{found} (expected {expected})"``, ``"{worst:.3g} mm"``).
Entries that depend on a count have plural forms (``msgid_plural`` and ``msgstr[0]``, …,
as the file's ``Plural-Forms`` header says), which Russian needs.

Code never holds a user-visible sentence: it holds a code and numbers (a :class:`Message`),
and the sentence is rendered here, in one place. A teacher adds a language by copying
``en.po`` to ``<lang>.po`` and translating every ``msgstr``; ``--lang <lang>`` then works
everywhere. The PO files are the one source: a language's file is compiled with Babel the
first time it is used and the compiled catalogue is kept in the user's cache folder
(``$XDG_CACHE_HOME/assur`` or ``~/.cache/assur``), named by the size and CRC-32 of the PO
file's content, so that later runs load it with :mod:`gettext` alone and an edited PO file is
compiled anew.

Examples
--------
>>> render("lang.unknown", "en", found="de", known="en, ru")
"no catalogue for language 'de'; the languages are en, ru"
>>> Message("lang.unknown", {"found": "de", "known": "en, ru"}).text("ru")
"нет каталога для языка 'de'; есть языки: en, ru"
>>> render("count.problems", "ru", n=5)
'5 ошибок'
"""

from __future__ import annotations

import gettext
import io
import os
import struct
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

__all__ = ["Message", "catalogue", "check_lang", "in_every_language", "joined", "language_key",
           "languages", "render"]

LOCALE = Path(__file__).with_name("locale")
DEFAULT = "en"


@cache
def languages() -> tuple[str, ...]:
    """The languages that have a catalogue file, English first."""
    found = sorted(p.stem for p in LOCALE.glob("*.po"))
    return tuple(sorted(found, key=lambda lang: (lang != DEFAULT, lang)))


def check_lang(lang: str) -> str:
    """Return ``lang`` if a catalogue exists for it.

    Raises
    ------
    ValueError
        If there is no ``assur/locale/<lang>.po``; the message lists the languages.
    """
    if lang not in languages():
        raise ValueError(render("lang.unknown", DEFAULT, found=lang,
                                known=", ".join(languages())))
    return lang


@cache
def catalogue(lang: str) -> gettext.GNUTranslations:
    """The compiled catalogue of ``lang`` (read once per process).

    Loaded from the cache folder when it holds the compilation of the PO file as it is now;
    otherwise compiled from the PO file and kept there (a cache that cannot be written is
    skipped).
    """
    source = (LOCALE / f"{lang}.po").read_bytes()
    compiled = _cached(lang, source)
    if compiled is not None:
        try:
            return gettext.GNUTranslations(io.BytesIO(compiled.read_bytes()))
        except (OSError, ValueError, LookupError, struct.error):
            pass  # a missing or damaged copy: compiled again below
    data = _compile(source)
    if compiled is not None:
        from assur.io.files import atomic_write_bytes

        try:
            atomic_write_bytes(compiled, data)
        except OSError:
            pass
    return gettext.GNUTranslations(io.BytesIO(data))


def _cached(lang: str, source: bytes) -> Path | None:
    """Where the compilation of this content of ``<lang>.po`` is kept; None without a home."""
    folder = os.environ.get("XDG_CACHE_HOME")
    try:
        base = Path(folder) if folder else Path.home() / ".cache"
    except RuntimeError:  # no home folder
        return None
    # the size and CRC-32 of the content name it (zlib is loaded anyway; hashlib would load
    # OpenSSL for a name that only tells the versions of one file apart)
    return base / "assur" / f"{lang}-{len(source):x}-{zlib.crc32(source):08x}.mo"


def _compile(source: bytes) -> bytes:
    """A PO file compiled to the MO form that :class:`gettext.GNUTranslations` reads."""
    from babel.messages.mofile import write_mo
    from babel.messages.pofile import read_po

    buffer = io.BytesIO()
    write_mo(buffer, read_po(io.BytesIO(source), locale=None), use_fuzzy=False)
    return buffer.getvalue()


def _lookup(code: str, lang: str, count: int | None) -> str | None:
    translations = catalogue(lang)
    missing = object()
    # GNUTranslations sets _catalog and plural while parsing; typeshed declares neither
    if count is None:
        found = translations._catalog.get(code, missing)  # type: ignore[attr-defined]
    else:
        index = translations.plural(count)  # type: ignore[attr-defined]
        found = translations._catalog.get((code, index), missing)  # type: ignore[attr-defined]
    return None if found is missing or found == "" else str(found)


def render(code: str, lang: str = DEFAULT, /, **data: Any) -> str:
    """The sentence of ``code`` in ``lang`` with ``data`` filled in.

    A plural entry takes its count from ``data["n"]``. A field whose value is a
    :class:`Message` (a part of the sentence, such as a description of a found value) is
    rendered in ``lang`` first. A code missing from a language falls back to English, and a
    code missing everywhere is shown as itself with its data, so a user never meets an
    exception here; the catalogue test keeps both from happening.
    """
    data = {key: value.text(lang) if isinstance(value, Message) else value
            for key, value in data.items()}
    count = data.get("n") if isinstance(data.get("n"), int) else None
    for language in (lang, DEFAULT):
        if language not in languages():
            continue
        template = _lookup(code, language, count)
        if template is None and count is not None:
            template = _lookup(code, language, None)
        if template is not None:
            try:
                return template.format(**data)
            except (KeyError, IndexError, ValueError):
                break
    shown = ", ".join(f"{k}={v!r}" for k, v in data.items())
    return f"{code}({shown})" if shown else code


@dataclass(frozen=True, slots=True)
class Message:
    """A sentence not yet rendered: its catalogue code and the numbers and names it shows.

    Results and errors carry messages, so one object can be shown in any language.
    """

    code: str
    data: Mapping[str, Any] = field(default_factory=dict)

    def text(self, lang: str = DEFAULT) -> str:
        """The sentence in ``lang``."""
        return render(self.code, lang, **self.data)

    def __str__(self) -> str:
        return self.text(DEFAULT)


def joined(parts: Sequence[Message], code: str = "term.list") -> Message:
    """Several messages as one: ``first, second, third`` (``code`` joins two parts).

    >>> joined([Message("count.problems", {"n": n}) for n in (1, 2, 5)]).text("ru")
    '1 ошибка, 2 ошибки, 5 ошибок'
    """
    if not parts:
        raise ValueError("joined() needs at least one message")
    whole = parts[0]
    for part in parts[1:]:
        whole = Message(code, {"first": whole, "rest": part})
    return whole


def in_every_language(key: str, message: Message) -> dict[str, str]:
    """A message rendered in every language, keyed ``key`` (English), ``key_ru``, …

    The form of the JSON answers, which carry each sentence in every language.

    >>> in_every_language("count", Message("count.problems", {"n": 2}))
    {'count': '2 problems', 'count_ru': '2 ошибки'}
    """
    return {language_key(key, lang): message.text(lang) for lang in languages()}


def language_key(key: str, lang: str) -> str:
    """The JSON key of a text in ``lang``: ``key`` in English, ``key_<lang>`` otherwise."""
    return key if lang == DEFAULT else f"{key}_{lang}"
