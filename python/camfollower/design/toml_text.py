# SPDX-License-Identifier: BSD-3-Clause
"""A parsed config (``Config.data``: dicts, lists, str, bool, int, float, dates) written back as TOML.

Reading the text with the library's reader gives the same dict: every float by ``repr`` (exact), every
string as a TOML basic string. Top-level scalars first, then tables as ``[a.b]`` headers, arrays of
tables as ``[[name]]`` blocks; a list of tables inside a table (a program's ``segments``) as inline
tables one per line, as docs/config.md writes them. Comments of the original file are not kept.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import re
from typing import Any, Dict, List

_BARE = re.compile(r"[A-Za-z0-9_-]+")


def key(name: str) -> str:
    """A TOML key: bare when it can be, else quoted."""
    return name if _BARE.fullmatch(name) else json.dumps(name, ensure_ascii=False)


def value(v: Any) -> str:
    """One TOML value (inline tables and arrays nested as needed)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # JSON's escapes are TOML basic-string escapes
    if isinstance(v, (_dt.datetime, _dt.date, _dt.time)):
        return v.isoformat()
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{key(k)} = {value(x)}" for k, x in v.items()) + " }" if v else "{}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x) for x in v) + "]"
    raise TypeError(f"cannot write a {type(v).__name__} as a TOML value: {v!r}")


def _is_table_array(v: Any) -> bool:
    return isinstance(v, list) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _table(lines: List[str], path: List[str], table: Dict[str, Any], header: str) -> None:
    scalars = [(k, v) for k, v in table.items() if not isinstance(v, dict) and not _is_table_array(v)]
    inline_arrays = [(k, v) for k, v in table.items() if _is_table_array(v) and path]
    subtables = [(k, v) for k, v in table.items() if isinstance(v, dict)]
    arrays = [(k, v) for k, v in table.items() if _is_table_array(v) and not path]
    if header and (scalars or inline_arrays or not (subtables or arrays)):
        lines.append("")
        lines.append(header)
    for k, v in scalars:
        lines.append(f"{key(k)} = {value(v)}")
    for k, v in inline_arrays:  # a program's segments: one inline table per line
        lines.append(f"{key(k)} = [")
        lines.extend(f"  {value(x)}," for x in v)
        lines.append("]")
    for k, v in subtables:
        sub = path + [key(k)]
        _table(lines, sub, v, "[" + ".".join(sub) + "]")
    for k, v in arrays:
        for item in v:
            lines.append("")
            lines.append(f"[[{key(k)}]]")
            for ik, iv in item.items():
                lines.append(f"{key(ik)} = {value(iv)}")


def dumps(data: Dict[str, Any], comment: str = "") -> str:
    """`data` (a parsed config) as TOML text, with `comment` lines on top."""
    lines: List[str] = [f"# {line}".rstrip() for line in comment.splitlines()]
    _table(lines, [], data, "")
    return "\n".join(lines).lstrip("\n") + "\n"


__all__ = ["dumps", "key", "value"]
