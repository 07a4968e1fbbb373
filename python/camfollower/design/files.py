# SPDX-License-Identifier: BSD-3-Clause
"""The design page's files: a config to open or save, cam exports, figures. Every path is inside the
working folder the page was started in (a name that leaves it, also through a symbolic link, is
refused); every file is written atomically by the package's one writer, never over a config the
page did not load, nor over its own config when that changed on disk since it was loaded."""

from __future__ import annotations

import copy
import hashlib
import os
from pathlib import Path
from typing import Any, Dict, Optional

from .. import _files
from . import toml_text

CONFIG_SUFFIX = ".toml"


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def inside(root: Path, name: Any, what: str, suffix: Optional[str] = None) -> Path:
    """`name` (relative to `root`, the working folder) as a path inside it, or ValueError naming
    `what` and why."""
    text = str(name or "").strip()
    if not text:
        raise ValueError(f"{what}: give a file name inside the working folder {root}")
    if "\0" in text:
        raise ValueError(f"{what}: a file name must not contain a NUL character")
    if suffix and not text.lower().endswith(suffix):
        raise ValueError(f"{what}: {text!r} must end in {suffix}")
    path = (root / text).resolve()
    if path != root and root not in path.parents:
        raise ValueError(
            f"{what}: {text!r} is outside the working folder {root}; the page reads and writes only inside it"
        )
    return path


def rebase(data: Dict[str, Any], old_dir: Path, new_dir: Path) -> Dict[str, Any]:
    """`data` with every relative data file (a lift table's ``file``) made relative to `new_dir`, so a
    config saved in another folder still finds its tables."""
    if old_dir.resolve() == new_dir.resolve():
        return data
    out = copy.deepcopy(data)

    def visit(node: Any) -> None:
        if isinstance(node, dict):
            f = node.get("file")
            if (
                isinstance(f, str)
                and not os.path.isabs(f)
                and ("theta_unit" in node or "law" in node or "h_unit" in node)
            ):
                node["file"] = os.path.relpath((old_dir / f).resolve(), new_dir.resolve())
            for v in node.values():
                visit(v)
        elif isinstance(node, list):
            for v in node:
                visit(v)

    visit(out.get("program", {}))
    return out


def save_config(
    root: Path, name: Any, data: Dict[str, Any], base_dir: Path, source: Optional[str], source_digest: Optional[str]
) -> Path:
    """Write `data` as a config file `name` in the working folder. Refused: a file that exists and is
    not this document's own config, or its own config changed on disk since the page loaded it
    (another tab or an editor saved it)."""
    path = inside(root, name, "save", CONFIG_SUFFIX)
    own = source is not None and Path(source).resolve() == path
    if path.exists():
        if not own:
            raise ValueError(
                f"save: {path.name} exists and is not the config this page opened; choose another name "
                "(the page never replaces a file it did not load)"
            )
        if source_digest and digest(path) != source_digest:
            raise ValueError(
                f"save: {path.name} was changed on disk since this page loaded it (another tab or an editor "
                "saved it); save under another name, or open it again to see that version"
            )
    text = toml_text.dumps(
        rebase(data, base_dir, path.parent),
        "A design saved by `camfollower design` (docs/design.md). Format: docs/config.md.",
    )
    _files.write_text(path, text)
    return path
