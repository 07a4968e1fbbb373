# SPDX-License-Identifier: BSD-3-Clause
"""The one writer for every output file of the package (figures, tables, NPZ, Parquet, summaries).

Everything goes through the compiled core's atomic writer: a uniquely named temporary in the target's
folder, then a rename, nothing left behind on failure. It refuses a target that is a directory, FIFO,
socket, device or symbolic link, a read-only file, a path holding a NUL, and the run's own input files.
A run writes ``summary.json`` last and removes an old one first (never when it is one of the run's
input files), so a folder holding a ``summary.json`` holds a complete run. Every JSON file is strict
(RFC 8259, ``json_text``): a non-finite number is written as ``null``.
"""

from __future__ import annotations

import io
import json
import math
import os
from pathlib import Path
from typing import Any, Iterable

from . import _core


def _path(path, parameter: str) -> str:
    try:
        text = os.fspath(path)
    except TypeError:
        raise TypeError(f"{parameter} must be a path (str or os.PathLike), got {type(path).__name__}") from None
    if isinstance(text, bytes):
        raise TypeError(f"{parameter} must be a str path, got bytes")
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        # A name the file system gave as bytes that are not UTF-8 (argv and os.listdir decode those with
        # surrogateescape): the core takes UTF-8 paths, so refuse it here, before any work is done.
        raise ValueError(
            f"{parameter}: the name {_shown(os.fsencode(text))} is not valid UTF-8; rename it or choose a UTF-8 name"
        ) from None
    return text


def _shown(value, limit: int = 200) -> str:
    """A path or value as messages echo it: repr (escaped), at most `limit` characters."""
    text = repr(value)
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


def _strict(value: Any) -> Any:
    """`value` as plain JSON types, every non-finite number (NaN, +-inf) as None."""
    if isinstance(value, dict):
        return {k if isinstance(k, str) else str(k): _strict(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_strict(v) for v in value]
    if isinstance(value, (bool, str, type(None))):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if hasattr(value, "tolist") and callable(value.tolist):  # numpy scalars and arrays
        return _strict(value.tolist())
    if isinstance(value, int):
        return int(value)
    if isinstance(value, float):
        return float(value) if math.isfinite(value) else None
    return value  # anything else: json.dumps raises TypeError, loudly


def json_text(value: Any, *, indent: int | None = 2) -> str:
    """`value` as strict JSON text (RFC 8259: non-finite numbers as null), ending in a newline when
    indented. The one JSON encoder of the package: ``allow_nan=False``, so a missed case fails."""
    text = json.dumps(_strict(value), indent=indent, allow_nan=False)
    return text + "\n" if indent is not None else text


def write_bytes(path, content: bytes, *, protect: Iterable = ()) -> Path:
    """Replace or create `path` with `content` atomically; `protect`: input files it must not be."""
    target = _path(path, "path")
    inputs = [_path(p, "protect") for p in protect]
    content = bytes(content)
    try:
        _core.write_file_atomically(target, content, inputs)
    except TypeError:  # pybind11's message would list the arguments, the whole content among them
        raise TypeError("write_file_atomically: path and protect must be str paths, content bytes") from None
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


def check_name(path, parameter: str) -> str:
    """Raise ValueError now (naming `parameter`) if `path` cannot name a file here: a NUL character or
    a name that is not UTF-8. Return it as a str."""
    text = _path(path, parameter)
    if "\0" in text:
        raise ValueError(f"{parameter}: the path contains a NUL character")
    return text


def check_target(path, *, protect: Iterable = ()) -> None:
    """Raise ValueError now if write_bytes would refuse `path` (before a long run)."""
    _core.check_output_target(_path(path, "path"), [_path(p, "protect") for p in protect])


def _same_file(a: os.stat_result, b: os.stat_result) -> bool:
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)


def output_folder(folder, parameter: str = "--out", *, protect: Iterable = ()) -> Path:
    """Create the output folder if needed and remove a previous run's summary.json (written last).

    `protect`: the run's input files. A summary.json that is one of them, or a link to one (symbolic
    or hard: the same device and inode), is never removed: ValueError naming `parameter` and the input.
    """
    inputs = [_path(p, "protect") for p in protect]
    folder = Path(check_name(folder, parameter))
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{parameter}: '{folder}' exists and is not a directory")
    folder.mkdir(parents=True, exist_ok=True)
    summary = folder / "summary.json"
    if summary.is_symlink() or summary.exists():
        if summary.is_dir():
            raise ValueError(f"{parameter}: '{summary}' is a directory; the run writes its summary there")
        entry = [os.lstat(summary)]  # the link itself, and what it resolves to
        try:
            entry.append(os.stat(summary))
        except OSError:
            pass  # a dangling link resolves to nothing
        for name in inputs:
            try:
                st = os.stat(name)
            except OSError:
                continue
            if any(_same_file(st, e) for e in entry):
                raise ValueError(
                    f"{parameter}: '{summary}' is the input file '{name}' (or a link to it); the run "
                    "would remove it as an old summary: choose another output folder"
                )
        summary.unlink()
    return folder
