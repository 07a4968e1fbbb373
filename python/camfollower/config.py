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
file, the line and the key; a bare-number length far off the scale of its contact (``h = 25`` for a
25 mm lift) is one of them, with a hint (docs/config.md, "Implausible lengths").

A mechanism whose follower is not held on its cam (no return spring, or a spring too weak for the
speed) is built, but ``load_config`` warns (:class:`ForceClosureWarning`, one per contact; the
messages are also in ``case.warnings``): see :func:`force_closure` and docs/config.md, "Force closure".
"""

from __future__ import annotations

import math
import numbers
import os
import re
import stat
import warnings as _warnings
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any, Dict, Optional, Tuple

from . import _core

_MAX_BYTES = 64 << 20


class ForceClosureWarning(UserWarning):
    """A contact whose follower is not held on its cam: nothing presses it on at rest, or, at the
    camshaft's speed, the rigid check's contact force falls below zero (docs/config.md, "Force closure")."""


def force_closure(mechanism, rpm: Optional[float] = None) -> Dict[str, Any]:
    """The force-closure checks of a mechanism (a ``Mechanism``, its ``MechanismBuilder`` or a
    :class:`Config`) at camshaft speed `rpm` (default: its own), over one revolution.

    Returns a dict: ``rpm``, ``angles`` (grid points per revolution), ``warnings`` (one message per
    contact that is not force-closed, naming the contact, the cam angles and the force) and
    ``contacts``: per contact ``contact``, ``static_min_force_N`` and ``static_min_angle_deg`` (the
    smallest contact force at rest), ``static_open_deg`` (cam-angle intervals where it is <= 0),
    ``rigid_min_force_N``, ``rigid_min_angle_deg`` and ``rigid_loss_deg`` (the rigid check at `rpm`),
    ``rigid_limit_rpm`` (the lowest speed at which the rigid check loses the contact; 0 when nothing
    presses it at rest, ``inf`` when no speed does), and for a grooved cam (form-closed, never warned
    about) ``grooved``, ``outer_flank_deg`` (cam-angle intervals where the rigid check puts the roller on
    the outer flank) and ``flank_changes`` (how often per revolution the load changes flank). Angles are
    each contact's cam angle in degrees.
    """
    if isinstance(mechanism, Config):
        mechanism = mechanism.builder
    builder = mechanism.builder() if hasattr(mechanism, "with_camshaft_speed_rpm") else mechanism
    if rpm is not None:
        lo, hi = _core.MIN_CAMSHAFT_SPEED * 30.0 / math.pi, _core.MAX_CAMSHAFT_SPEED * 30.0 / math.pi
        if isinstance(rpm, bool) or not isinstance(rpm, numbers.Real) or not lo <= float(rpm) <= hi:
            raise ValueError(f"rpm must be a camshaft speed in [{lo:.6g}, {hi:.6g}] rpm, got {rpm!r}")
        rpm = float(rpm)
    return _core._force_closure(builder, 0.0 if rpm is None else rpm)


@dataclass(frozen=True)
class Config:
    """One case read from a config file.

    ``programs``: the motion programs by name; ``builder``: the mechanism's description
    (``MechanismBuilder``); ``mechanism``: the built, immutable ``Mechanism``; ``solver``: keyword
    arguments of :func:`camfollower.simulate` (``time_step`` resolved from ``steps_per_revolution``;
    as objects: ``settings``, a :class:`camfollower.SolverSettings`, and ``options``, a
    :class:`camfollower.RunOptions`);
    ``output``: the ``[output]`` table (``file``, ``decimation``, ``record_last_revolutions``);
    ``data``: the parsed TOML as a dict; ``path``: the file (None for a dict); ``warnings``: the
    force-closure warnings at the config's speed (computed on first use; ``load_config`` issues them
    as :class:`ForceClosureWarning`, ``config_from_dict`` only keeps them here).
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

    @property
    def settings(self):
        """The config's :class:`camfollower.SolverSettings` (``[solver]``)."""
        from .simulation import settings_and_options

        return settings_and_options(**self.simulate_kwargs())[0]

    @property
    def options(self):
        """The config's :class:`camfollower.RunOptions` (``[solver]`` and ``[output]``)."""
        from .simulation import settings_and_options

        return settings_and_options(**self.simulate_kwargs())[1]

    def run(self, **overrides):
        """Simulate the case (``overrides`` replace the config's ``simulate`` keyword arguments)."""
        from .simulation import simulate

        return simulate(self.mechanism, self.settings, self.options, **overrides)

    def force_closure(self, rpm: Optional[float] = None) -> Dict[str, Any]:
        """:func:`force_closure` of this case's mechanism (at `rpm`, default the config's speed)."""
        return force_closure(self.builder, rpm)

    @cached_property
    def warnings(self) -> Tuple[str, ...]:
        """The force-closure warnings at the config's speed (docs/config.md, "Force closure")."""
        return tuple(self.force_closure()["warnings"])


def _case(raw: dict, data: dict, path: Optional[Path]) -> Config:
    builder = raw["builder"]
    return Config(
        path=path,
        data=data,
        preset=raw["preset"],
        programs=dict(raw["programs"]),
        builder=builder,
        mechanism=builder.build(),
        solver=dict(raw["solver"]),
        output=dict(raw["output"]),
    )


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
    case = _case(raw, data, p)
    for message in case.warnings:
        _warnings.warn(f"{p}: {message}", ForceClosureWarning, stacklevel=2)
    return case


def config_from_dict(data: Dict[str, Any], base_dir: os.PathLike | str = ".") -> Config:
    """Build a case from a dict shaped like a parsed config (e.g. ``load_config(...).data``, changed).

    Keys and values follow docs/config.md; errors name the key path (there are no line numbers).
    Tables and lists nested more than 64 levels deep (a cyclic dict among them) are refused.
    """
    if not isinstance(data, dict):
        raise ValueError(f"data must be a dict shaped like a config file, got {type(data).__name__}")
    raw = _core._case_from_dict(data, "<dict>", os.fspath(base_dir))
    return _case(raw, data, None)


_SINE_CONSTANT_COSINE = re.compile(r"sine_constant_cosine\(b=([^,]+), c=([^,]+), d=([^)]+)\)")


def program_toml(program, name: str, *, rotary: bool = False) -> str:
    """``program`` as a config's ``[program.<name>]`` table (docs/config.md), numbers in SI (rad, and m
    or rad for an arm's lift: ``rotary``) written to round-trip exactly: loading it gives the same
    program. Catalogue laws by name, spline and table segments by their tables; a polynomial segment
    (its conditions are not kept) or a program that does not start at 0 is refused."""
    if not isinstance(program, _core.MotionProgram):
        raise TypeError(f"program must be a MotionProgram, got {type(program).__name__}")
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_-]*", name or ""):
        raise ValueError(f"name must be a bare TOML key (letters, digits, _ and -), got {name!r}")
    h_unit = "rad" if rotary else "m"
    segments = list(program.segments)
    first = segments[0]
    if first.law.is_custom and first.law.definition.get("periodic"):
        d = first.law.definition
        return (
            f"[program.{name}]\ntheta_unit = \"rad\"\nh_unit = \"{h_unit}\"\ndegree = {d['degree']}\n"
            f"smoothing = {d['smoothing']!r}\ntheta = {_floats(d['theta'])}\nh = {_floats(d['h'])}\n"
        )
    if abs(first.theta_start) > 1e-12:
        raise ValueError(f"program: starts at {first.theta_start!r} rad; a config's program starts at 0")
    rows = []
    for i, s in enumerate(segments):
        law = s.law
        if law.is_custom:
            d = law.definition
            if "theta" not in d:
                raise ValueError(f"program: segment {i} is a polynomial ({law.name}); write its conditions by hand")
            rows.append(
                f'  {{ law = "table", theta_unit = "rad", h_unit = "{h_unit}", degree = {d["degree"]}, '
                f'smoothing = {d["smoothing"]!r}, theta = {_floats(d["theta"])}, h = {_floats(d["h"])}, '
                f'start_derivatives = {_floats(d["start_derivatives"])}, end_derivatives = {_floats(d["end_derivatives"])} }},'
            )
            continue
        scc = _SINE_CONSTANT_COSINE.fullmatch(law.name)
        extra = f", b = {float(scc[1])!r}, c = {float(scc[2])!r}, d = {float(scc[3])!r}" if scc else ""
        kind = "sine_constant_cosine" if scc else law.name
        rows.append(f'  {{ law = "{kind}", end = {s.theta_end!r}, h = {s.h_end!r}{extra} }},')
    return f"[program.{name}]\nsegments = [\n" + "\n".join(rows) + "\n]\n"


def _floats(values) -> str:
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


__all__ = ["Config", "ForceClosureWarning", "config_from_dict", "force_closure", "load_config", "program_toml"]
