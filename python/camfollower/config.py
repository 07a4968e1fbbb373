# SPDX-License-Identifier: BSD-3-Clause
"""Config files: a whole case (motion programs, mechanism, solver, output) in one TOML file.

The format is documented in docs/config.md; the command line (``camfollower run CONFIG``) reads the
same files with the same rules, so a config means the same thing in both.

>>> import camfollower as cf
>>> case = cf.load_config("examples/flat_faced_table.toml")     # doctest: +SKIP
>>> result = case.run()                                           # doctest: +SKIP

``load_config`` parses the file with the library's TOML parser (toml++, the command line's), so a file
reads the same in both, byte order mark, nesting limits and messages included; ``case.data`` is the
parsed table as a dict (tables as dicts in the file's order, arrays as lists, dates as ``datetime``
objects), to inspect or change and pass to ``config_from_dict``. Errors are ``ValueError`` naming the
file, the line and the key.
"""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Optional

from . import _core

_MAX_BYTES = 64 << 20


@dataclass(frozen=True)
class Config:
    """One case read from a config file.

    ``programs``: the motion programs by name; ``builder``: the mechanism's description
    (``MechanismBuilder``); ``mechanism``: the built, immutable ``Mechanism``; ``solver``: keyword
    arguments of :func:`camfollower.simulate` (``time_step`` resolved from ``steps_per_revolution``);
    ``output``: the ``[output]`` table (``file``, ``decimation``, ``record_last_revolutions``);
    ``data``: the parsed TOML as a dict; ``path``: the file (None for a dict).
    """

    path: Optional[Path]
    data: Dict[str, Any]
    preset: str
    programs: Dict[str, Any]
    builder: Any
    mechanism: Any
    solver: Dict[str, Any] = field(default_factory=dict)
    output: Dict[str, Any] = field(default_factory=dict)

    def simulate_kwargs(self) -> Dict[str, Any]:
        """The keyword arguments of ``camfollower.simulate`` this config asks for."""
        kw = dict(self.solver)
        steps = kw.pop("steps_per_revolution", None)
        if steps is not None:
            kw["time_step"] = self.mechanism.period / steps
        kw["decimation"] = int(self.output.get("decimation", 1))
        if "record_last_revolutions" in self.output:
            kw["record_last_revolutions"] = self.output["record_last_revolutions"]
        return kw

    def run(self, **overrides):
        """Simulate the case (``overrides`` replace the config's ``simulate`` keyword arguments)."""
        from .simulation import simulate

        return simulate(self.mechanism, **{**self.simulate_kwargs(), **overrides})


def _case(raw: dict, data: dict, path: Optional[Path]) -> Config:
    builder = raw["builder"]
    return Config(path=path, data=data, preset=raw["preset"], programs=dict(raw["programs"]), builder=builder,
                  mechanism=builder.build(), solver=dict(raw["solver"]), output=dict(raw["output"]))


def load_config(path: os.PathLike | str) -> Config:
    """Read a config file (docs/config.md). Relative data files (lift tables) are found next to it.

    Raises ValueError naming the file (and line and key) for a missing, empty or non-regular file,
    a TOML syntax error, an unknown or misplaced key, or a value out of range.
    """
    p = Path(os.fspath(path))
    if "\0" in str(p):
        raise ValueError(f"config path must not contain a NUL character: {str(p)!r}")
    try:
        str(p).encode("utf-8")
    except UnicodeEncodeError:  # undecodable bytes (surrogateescape): the library's reader takes UTF-8
        raise ValueError(f"config path {os.fsencode(str(p))!r} is not valid UTF-8; rename the file") from None
    try:
        st = p.stat()
    except OSError as e:
        raise ValueError(f"config '{p}': {e.strerror or e}") from None
    if stat.S_ISDIR(st.st_mode):
        raise ValueError(f"config '{p}' is a directory, not a config file")
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"config '{p}' is not a regular file")
    if st.st_size == 0:
        raise ValueError(f"config '{p}' is empty")
    if st.st_size > _MAX_BYTES:
        raise ValueError(f"config '{p}' is larger than 64 MiB; put large lift tables in a data file")
    # The bytes go to the library's reader as they are: it checks the UTF-8, parses and builds, with
    # the command line's messages (file:line:key) and limits.
    data, raw = _core._read_config(p.read_bytes(), str(p), str(p.parent))
    return _case(raw, data, p)


def config_from_dict(data: Dict[str, Any], base_dir: os.PathLike | str = ".") -> Config:
    """Build a case from a dict shaped like a parsed config (e.g. ``load_config(...).data``, changed).

    Keys and values follow docs/config.md; errors name the key path (there are no line numbers).
    Tables and lists nested more than 64 levels deep (a cyclic dict among them) are refused.
    """
    if not isinstance(data, dict):
        raise ValueError(f"data must be a dict shaped like a config file, got {type(data).__name__}")
    raw = _core._case_from_dict(data, "<dict>", os.fspath(base_dir))
    return _case(raw, data, None)


__all__ = ["Config", "load_config", "config_from_dict"]
