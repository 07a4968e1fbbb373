# SPDX-License-Identifier: BSD-3-Clause
"""The one writer for every output file of the package (figures, tables, NPZ, Parquet, summaries).

Everything goes through the compiled core's atomic writer: a uniquely named temporary in the target's
folder, then a rename, nothing left behind on failure. It refuses a target that is a directory, FIFO,
socket, device or symbolic link, a read-only file, a path holding a NUL, and the run's own input files.
A run writes ``summary.json`` last and removes an old one first, so a folder holding a
``summary.json`` holds a complete run.
"""

from __future__ import annotations

import io
import os
from pathlib import Path
from typing import Iterable

from . import _core


def _path(path, parameter: str) -> str:
    try:
        text = os.fspath(path)
    except TypeError:
        raise TypeError(f"{parameter} must be a path (str or os.PathLike), got {type(path).__name__}") from None
    if isinstance(text, bytes):
        raise TypeError(f"{parameter} must be a str path, got bytes")
    return text


def write_bytes(path, content: bytes, *, protect: Iterable = ()) -> Path:
    """Replace or create `path` with `content` atomically; `protect`: input files it must not be."""
    target = _path(path, "path")
    _core.write_file_atomically(target, bytes(content), [_path(p, "protect") for p in protect])
    return Path(target)


def write_text(path, text: str, *, protect: Iterable = ()) -> Path:
    return write_bytes(path, text.encode("utf-8"), protect=protect)


def save_figure(fig, path, *, protect: Iterable = (), dpi: int = 110) -> Path:
    """Render a matplotlib figure to PNG in memory, write it atomically and close the figure."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, dpi=dpi, format="png")
    finally:
        plt.close(fig)
    return write_bytes(path, buffer.getvalue(), protect=protect)


def check_target(path, *, protect: Iterable = ()) -> None:
    """Raise ValueError now if write_bytes would refuse `path` (before a long run)."""
    _core.check_output_target(_path(path, "path"), [_path(p, "protect") for p in protect])


def output_folder(folder, parameter: str = "--out") -> Path:
    """Create the output folder if needed and remove a previous run's summary.json (written last)."""
    folder = Path(_path(folder, parameter))
    if "\0" in str(folder):
        raise ValueError(f"{parameter}: the path contains a NUL character")
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{parameter}: '{folder}' exists and is not a directory")
    folder.mkdir(parents=True, exist_ok=True)
    summary = folder / "summary.json"
    if summary.is_symlink() or summary.exists():
        if summary.is_dir():
            raise ValueError(f"{parameter}: '{summary}' is a directory; the run writes its summary there")
        summary.unlink()
    return folder
