"""Writing a case's picture: drawn in memory, then written atomically."""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import Any

from assur.io.files import atomic_write_bytes

__all__ = ["write_figure"]


def write_figure(figure: Any, path: str | os.PathLike[str], *, dpi: int = 120) -> Path:
    """Write a matplotlib figure to ``path`` atomically; the format follows the file suffix.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
    path : str or path-like
        A file without a suffix is written as PNG.
    dpi : int
        Dots per inch.

    Returns
    -------
    Path
        The file written.
    """
    path = Path(path)
    buffer = io.BytesIO()
    figure.savefig(buffer, format=path.suffix.lstrip(".").lower() or "png", dpi=dpi)
    atomic_write_bytes(path, buffer.getvalue())
    return path
