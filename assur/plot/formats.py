"""Picture and animation formats: which a file name asks for, and the bytes of a figure in it.

A picture is written in the format its file name ends with: PNG, SVG, PDF or JPEG
(:data:`PICTURE_FORMATS`); an animation as a GIF, or as an MP4 where matplotlib finds an
ffmpeg writer (:func:`animation_formats`). Any other ending is refused by
:func:`picture_format` and :func:`animation_format` with a :class:`PictureFormatError` that
names the file and the formats supported, before anything is computed or written.
"""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from assur.errors import AssurError
from assur.text import Message

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["PICTURE_FORMATS", "PictureFormatError", "animation_format", "animation_formats",
           "figure_bytes", "picture_format"]

#: File ending → the format name matplotlib writes it with.
PICTURE_FORMATS: dict[str, str] = {"png": "png", "svg": "svg", "pdf": "pdf", "jpg": "jpeg",
                                   "jpeg": "jpeg"}


class PictureFormatError(AssurError, ValueError):
    """A picture or animation was asked for in a format that cannot be written.

    Parameters
    ----------
    message : Message
        The sentence (file, ending found, formats supported) in any catalogue language.
    """

    def __init__(self, message: Message) -> None:
        self.message = message
        super().__init__(message.text("en"))

    def text(self, lang: str = "en") -> str:
        """The message in ``lang``."""
        return self.message.text(lang)


def _ending(path: str | os.PathLike[str]) -> str:
    return Path(path).suffix.lower().lstrip(".")


def _listed(endings: list[str]) -> str:
    return ", ".join(f".{e}" for e in endings)


def picture_format(path: str | os.PathLike[str], allowed: tuple[str, ...] = tuple(PICTURE_FORMATS)
                   ) -> str:
    """The format a picture file name asks for.

    Parameters
    ----------
    path : path-like
        The file to be written.
    allowed : tuple of str
        The endings accepted (default: every one of :data:`PICTURE_FORMATS`).

    Returns
    -------
    str
        The matplotlib format name (``"png"``, ``"svg"``, ``"pdf"``, ``"jpeg"``).

    Raises
    ------
    PictureFormatError
        For any other ending.

    Examples
    --------
    >>> picture_format("scheme.SVG"), picture_format("photo.jpg")
    ('svg', 'jpeg')
    >>> picture_format("a.bmp")  # doctest: +IGNORE_EXCEPTION_DETAIL
    Traceback (most recent call last):
    PictureFormatError: a.bmp: a picture cannot be written as '.bmp'; supported: ...
    """
    ending = _ending(path)
    if ending not in allowed:
        raise PictureFormatError(Message("plot.format_unsupported", {
            "path": str(path), "found": f".{ending}" if ending else "''",
            "supported": _listed(list(allowed))}))
    return PICTURE_FORMATS[ending]


def animation_formats() -> list[str]:
    """The animation endings that can be written here: ``gif`` always, ``mp4`` where
    matplotlib has an ffmpeg writer."""
    from matplotlib.animation import writers

    return ["gif"] + (["mp4"] if writers.is_available("ffmpeg") else [])


def animation_format(path: str | os.PathLike[str]) -> str:
    """The format an animation file name asks for (``"gif"`` or ``"mp4"``).

    Raises
    ------
    PictureFormatError
        For another ending, or for ``.mp4`` where no ffmpeg writer is available (the
        message names the formats that can be written).
    """
    ending, available = _ending(path), animation_formats()
    if ending in available:
        return ending
    code = "plot.mp4_unavailable" if ending == "mp4" else "plot.animation_unsupported"
    raise PictureFormatError(Message(code, {
        "path": str(path), "found": f".{ending}" if ending else "''",
        "supported": _listed(available)}))


def figure_bytes(fig: Figure, fmt: str, *, dpi: int = 120, tight: bool = True) -> bytes:
    """A figure as the bytes of a file in ``fmt`` (a value of :data:`PICTURE_FORMATS`).

    SVG keeps its texts as text and carries no date, so the same figure gives the same file.
    """
    import matplotlib

    options: dict[str, Any] = {"format": fmt, "dpi": dpi}
    if tight:
        options["bbox_inches"] = "tight"
    if fmt in ("svg", "pdf"):
        options["metadata"] = {"Date": None} if fmt == "svg" else {"CreationDate": None}
    buffer = io.BytesIO()
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": "assur"}):
        fig.savefig(buffer, **options)
    return buffer.getvalue()
