# SPDX-License-Identifier: BSD-3-Clause
"""The [sweep] and [montecarlo] tables of a config file (docs/studies.md), read and checked.

    [sweep]
    rpm = [500, 750, 1000]            # or rpm_from / rpm_to / count (evenly spaced)
    jump = [1000, 2000]               # optional: the first contact loss in this speed range (rpm)
    accuracy = 1e-3                   # optional: of force and acceleration, relative to their peaks
    accuracy_of = "force"             # optional: the accuracy of the contact force alone
    steps_per_revolution = 16384      # optional: a fixed step instead of the accuracy
    contact = "cam"                   # optional: the contact to measure (default: the first)

    [montecarlo]
    cases = 200
    seed = 1
    rpm = 900                         # optional: every case at this camshaft speed (default: the config's)
    roller_tolerance = "fixed_cam"    # optional: or "regenerated_cam" (camfollower.tolerance)
    [[montecarlo.tolerance]]
    parameter = "preset.parameters.contact_stiffness"   # key path of a numeric value in this file
    distribution = "normal"                             # normal | uniform | truncated_normal
    std = 0.05
    relative = true

    [synthesis]                       # camfollower synthesize (docs/synthesis.md); every key optional
    output = "slide"                  # the DOF whose motion is designed (default: the follower's)
    objective = "residual"            # residual | follower_error | acceleration
    band = 0.2                        # +/-20 % of the config's speed (or rpm = [design, ...])
    max_acceleration = 30.0           # m/s^2 (rad/s^2 for an arm), rigid follower at the design speed

Unknown keys and bad values are refused, naming the file, the line and the key (the line from the
library's TOML parser, the one the file was read with); given the case's ``build`` (a
:class:`camfollower.tolerance.ConfigCase`) and ``contacts``, so are a tolerance on a value the config
does not hold or the model refuses, and a contact the mechanism does not have.
"""

from __future__ import annotations

import dataclasses
import datetime
import math
import re
from typing import Any, Dict, Optional, Sequence

from . import _core
from .response import ACCURACY_OF, check_accuracy, check_accuracy_of
from .speed import _MAX_RPM, _MIN_RPM
from .tolerance import DISTRIBUTIONS, ROLLER_TOLERANCES, _check_ranges


def _shown(value, limit: int = 60) -> str:
    """A value or key as messages echo it: repr (control characters escaped), at most `limit`
    characters, so an error never carries megabytes of input or a terminal escape."""
    text = value if isinstance(value, str) and value.isprintable() else repr(value)
    text = "".join(c if c.isprintable() else "?" for c in text)
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


def _a(value) -> str:
    """The TOML type of a value as messages name it: "a table", "an array", ..."""
    name = type(value).__name__
    for kind, toml_name in (
        (bool, "boolean"),
        (int, "integer"),
        (float, "float"),
        (str, "string"),
        (list, "array"),
        (dict, "table"),
        (datetime.date, "date"),
        (datetime.time, "time"),
    ):
        if isinstance(value, kind):
            name = toml_name
            break
    return ("an " if name[0] in "aeiou" else "a ") + name


def _line(path, key: str) -> Optional[int]:
    """The line of `key` ("sweep.rpm[0]", "montecarlo.tolerance[1].std") in the file, or of its
    deepest part that is there: positions from the library's TOML parser; None when not found."""
    try:
        with open(path, "rb") as f:
            text = f.read(64 << 20)
    except (OSError, TypeError, ValueError):
        return None
    parts = [int(index) if index else name for name, index in re.findall(r"([^.\[\]]+)|\[(\d+)\]", key)]
    return _core._toml_line(text, parts)


def _where(path, key: str) -> str:
    """file:line: key (or key alone without a file)."""
    if not path:
        return _shown(key, 200)
    line = _line(path, key)
    return f"{path}:{line}: {_shown(key, 200)}" if line else f"{path}: {_shown(key, 200)}"


def _unknown(table: Dict[str, Any], known, path, prefix: str) -> None:
    extra = [k for k in table if k not in known]
    if extra:
        raise ValueError(f"{_where(path, prefix + '.' + extra[0])}: unknown key; known here: {', '.join(known)}")


def _int(table, key, default, lo, hi, path, prefix):
    v = table.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise ValueError(
            f"{_where(path, prefix + '.' + key if prefix else key)}: must be an integer in [{lo}, {hi}], "
            f"got {_shown(v)}"
        )
    return v


def _contact(table, key: str, path, contacts: Optional[Sequence[str]]):
    contact = table.get("contact")
    if contact is not None and not isinstance(contact, str):
        raise ValueError(f"{_where(path, key)}: must be a contact's name (a string), got {_a(contact)}")
    if contact is not None and contacts is not None and contact not in contacts:
        raise ValueError(
            f"{_where(path, key)}: no contact named {_shown(contact)}; the mechanism's contacts: "
            f"{', '.join(_shown(c) for c in contacts[:20])}"
        )
    return contact


def _tolerance(block, key: str, path):
    """One [[montecarlo.tolerance]] block: (parameter, distribution). Every key of the block is
    checked here, so a message names the one at fault, its line and what it must be."""
    if not isinstance(block, dict):
        raise ValueError(f"{_where(path, key)}: must be a table, got {_a(block)}")
    for required in ("parameter", "distribution"):
        if required not in block:
            raise ValueError(f"{_where(path, key)}: the key {required!r} is required here")
    name = block["parameter"]
    if not isinstance(name, str) or not name:
        got = "an empty string" if name == "" else _a(name)
        raise ValueError(
            f"{_where(path, key + '.parameter')}: must name a numeric value of this file by its key path "
            f"(a string), got {got}"
        )
    kind = block["distribution"]
    if not isinstance(kind, str) or kind not in DISTRIBUTIONS:
        got = _shown(kind) if isinstance(kind, str) else _a(kind)
        raise ValueError(
            f"{_where(path, key + '.distribution')}: must be one of {', '.join(DISTRIBUTIONS)} (a string), got {got}"
        )
    cls = DISTRIBUTIONS[kind]
    fields = [f.name for f in dataclasses.fields(cls)]
    _unknown(block, ("parameter", "distribution", *fields), path, key)
    for f in dataclasses.fields(cls):
        if f.name not in block and f.default is dataclasses.MISSING:
            raise ValueError(f"{_where(path, key)}: a {kind} distribution needs the key {f.name!r}")
    try:
        return name, cls(**{k: block[k] for k in fields if k in block})
    except ValueError as e:
        # The distribution's message names its field ("Normal std must be ..."): locate it there.
        field = next((k for k in fields if k in block and re.search(rf"\b{k}\b", str(e))), None)
        raise ValueError(f"{_where(path, key + '.' + field if field else key)}: {_shown(str(e), 400)}") from None


def _speed(v, key, path) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and _MIN_RPM <= v <= _MAX_RPM):
        raise ValueError(
            f"{_where(path, key)}: must be a camshaft speed in [{_MIN_RPM:.6g}, {_MAX_RPM:.6g}] rpm, got {_shown(v)}"
        )
    return float(v)


def sweep_settings(table: Dict[str, Any], *, rpm=None, jump=None, path=None, contacts=None) -> Dict[str, Any]:
    """Speeds, optional jump bracket, steps per revolution and contact from a [sweep] table, with
    command-line overrides (``rpm``, ``jump``); ``contacts``: the mechanism's contact names, to check
    ``contact`` against."""
    if not isinstance(table, dict):
        raise ValueError(f"{_where(path, 'sweep')}: must be a table, got {_a(table)}")
    _unknown(
        table,
        ("rpm", "rpm_from", "rpm_to", "count", "jump", "accuracy", "accuracy_of", "steps_per_revolution", "contact"),
        path,
        "sweep",
    )
    if rpm:
        speeds = [_speed(float(r), "--rpm", None) for r in rpm]
    elif "rpm" in table:
        if "rpm_from" in table or "rpm_to" in table or "count" in table:
            raise ValueError(f"{_where(path, 'sweep.rpm')}: give rpm (a list) or rpm_from/rpm_to/count, not both")
        if not isinstance(table["rpm"], list) or not table["rpm"]:
            raise ValueError(
                f"{_where(path, 'sweep.rpm')}: must be a non-empty array of speeds (rpm), got "
                f"{'an empty array' if table['rpm'] == [] else _a(table['rpm'])}"
            )
        speeds = [_speed(r, f"sweep.rpm[{i}]", path) for i, r in enumerate(table["rpm"])]
    elif "rpm_from" in table or "rpm_to" in table:
        lo, hi = (
            _speed(table.get("rpm_from"), "sweep.rpm_from", path),
            _speed(table.get("rpm_to"), "sweep.rpm_to", path),
        )
        if not lo < hi:
            raise ValueError(f"{_where(path, 'sweep.rpm_to')}: must be above rpm_from ({lo:g}), got {hi:g}")
        n = _int(table, "count", 20, 2, 10000, path, "sweep")
        speeds = [lo + (hi - lo) * i / (n - 1) for i in range(n)]
    else:
        raise ValueError(f"{_where(path, 'sweep')}: give the speeds: rpm = [...] or rpm_from, rpm_to, count (or --rpm)")
    # The bracket is checked whole here, before any run: from the command line (named --jump) or the file.
    bracket, key, where = (jump, "--jump", None) if jump else (table.get("jump"), "sweep.jump", path)
    if bracket is not None:
        if not isinstance(bracket, (list, tuple)) or len(bracket) != 2:
            raise ValueError(f"{_where(where, key)}: must be two speeds [lo, hi] in rpm, got {_shown(bracket)}")
        bracket = [_speed(b, key, where) for b in bracket]
        if not bracket[0] < bracket[1]:
            raise ValueError(
                f"{_where(where, key)}: the low speed {bracket[0]:g} must be below the high speed {bracket[1]:g} rpm"
            )
    contact = _contact(table, "sweep.contact", path, contacts)
    steps = (
        _int(table, "steps_per_revolution", None, 64, 1 << 22, path, "sweep")
        if "steps_per_revolution" in table
        else None
    )
    return {
        "rpm": speeds,
        "jump": bracket,
        "contact": contact,
        "accuracy": _accuracy(table, path, "sweep"),
        "accuracy_of": _accuracy_of(table, path, "sweep"),
        "steps_per_revolution": steps,
    }


def _accuracy(table, path, prefix) -> Optional[float]:
    """The table's study accuracy (None: the default, or the fixed steps_per_revolution)."""
    accuracy = table.get("accuracy")
    if accuracy is None:
        return None
    try:
        return check_accuracy(accuracy, "accuracy")
    except ValueError as e:
        raise ValueError(f"{_where(path, prefix + '.accuracy')}: {str(e).removeprefix('accuracy ')}") from None


def _accuracy_of(table, path, prefix) -> str:
    """What the table's study accuracy covers (response.ACCURACY_OF; the first by default)."""
    try:
        return check_accuracy_of(table.get("accuracy_of", ACCURACY_OF[0]), "accuracy_of")
    except ValueError as e:
        raise ValueError(f"{_where(path, prefix + '.accuracy_of')}: {str(e).removeprefix('accuracy_of ')}") from None


def montecarlo_settings(
    table: Optional[Dict[str, Any]], *, cases=None, seed=None, rpm=None, path=None, build=None, contacts=None
) -> Dict[str, Any]:
    """Cases, seed, camshaft speed, roller tolerance, steps per revolution, contact and the tolerances
    {key path: distribution} from a [montecarlo] table, with command-line overrides (``cases``, ``seed``,
    ``rpm``). Given the model's ``build`` (a ConfigCase), it is set to the table's speed and roller
    tolerance (returned as ``build``), each tolerance's value is looked up and the model built at the
    distribution's ends, as monte_carlo does, so that a refusal names the block's ``parameter`` line;
    ``contacts`` as in sweep_settings. ``rpm`` is None when neither the table nor the override gives it
    (the config's own speed)."""
    if table is None:
        raise ValueError(
            f"{_where(path, 'montecarlo')}: the config has no [montecarlo] table with its tolerances (docs/studies.md)"
        )
    if not isinstance(table, dict):
        raise ValueError(f"{_where(path, 'montecarlo')}: must be a table, got {_a(table)}")
    _unknown(
        table,
        (
            "cases",
            "seed",
            "rpm",
            "roller_tolerance",
            "accuracy",
            "accuracy_of",
            "steps_per_revolution",
            "contact",
            "tolerance",
        ),
        path,
        "montecarlo",
    )
    # The speed: --rpm (named so) over the table's rpm; checked before any model is built.
    if rpm is not None:
        speed = _speed(rpm, "--rpm", None)
    elif "rpm" in table:
        speed = _speed(table["rpm"], "montecarlo.rpm", path)
    else:
        speed = None
    mode = table.get("roller_tolerance", "fixed_cam")
    if not isinstance(mode, str) or mode not in ROLLER_TOLERANCES:
        got = _shown(mode) if isinstance(mode, str) else _a(mode)
        raise ValueError(
            f"{_where(path, 'montecarlo.roller_tolerance')}: must be one of "
            f"{', '.join(ROLLER_TOLERANCES)} (a string), got {got}"
        )
    if build is not None:
        build = build.with_options(roller_tolerance=mode, camshaft_speed_rpm=speed)
    blocks = table.get("tolerance")
    if not isinstance(blocks, list) or not blocks:
        got = "" if blocks is None or blocks == [] else f", got {_a(blocks)}"
        raise ValueError(
            f"{_where(path, 'montecarlo.tolerance')}: give at least one [[montecarlo.tolerance]] block{got}"
        )
    tolerances = {}
    for i, b in enumerate(blocks):
        key = f"montecarlo.tolerance[{i}]"
        name, dist = _tolerance(b, key, path)
        if name in tolerances:
            raise ValueError(f"{_where(path, key + '.parameter')}: {_shown(name)} has two tolerances")
        tolerances[name] = dist
        if build is not None:
            try:
                _check_ranges(build, {name: dist}, {name: build.nominal(name)})
            except (ValueError, RuntimeError) as e:  # RuntimeError: a model whose equilibrium is not found
                kind = ValueError if isinstance(e, ValueError) else RuntimeError
                raise kind(f"{_where(path, key + '.parameter')}: {_shown(str(e), 1000)}") from None
    # Overrides (the command line's --cases, --seed) obey the table's ranges, named as options.
    cases = (
        _int(table, "cases", 100, 1, 10_000_000, path, "montecarlo")
        if cases is None
        else _int({"--cases": cases}, "--cases", None, 1, 10_000_000, None, "")
    )
    seed = (
        _int(table, "seed", 0, 0, 2**63 - 1, path, "montecarlo")
        if seed is None
        else _int({"--seed": seed}, "--seed", None, 0, 2**63 - 1, None, "")
    )
    contact = _contact(table, "montecarlo.contact", path, contacts)
    out = {
        "tolerances": tolerances,
        "cases": cases,
        "seed": seed,
        "contact": contact,
        "rpm": speed,
        "roller_tolerance": mode,
        "accuracy": _accuracy(table, path, "montecarlo"),
        "accuracy_of": _accuracy_of(table, path, "montecarlo"),
        "steps_per_revolution": _int(table, "steps_per_revolution", None, 64, 1 << 22, path, "montecarlo")
        if "steps_per_revolution" in table
        else None,
    }
    if build is not None:
        out["build"] = build
    return out


#: The [synthesis] table's keys beyond contact (docs/synthesis.md): name -> (kind, low, high).
_SYNTHESIS_NUMBERS = {
    "band": (float, 0.0, 0.99),
    "band_speeds": (int, 2, 21),
    "nodes": (int, 3, 40),
    "continuity": (int, 2, 6),
    "max_acceleration": (float, 0.0, math.inf),
    "max_jerk": (float, 0.0, math.inf),
    "max_pressure_angle_deg": (float, 0.0, 90.0),
    "min_radius": (float, 0.0, math.inf),
    "min_force": (float, -math.inf, math.inf),
    "max_output_acceleration": (float, 0.0, math.inf),
    "max_stress": (float, 0.0, math.inf),
    "roller_width": (float, 0.0, 1.0),
    "steps_per_revolution": (int, 64, 1 << 22),
    "max_iterations": (int, 1, 100),
    "max_evaluations": (int, 2, 100000),
    "tolerance": (float, 1e-8, 0.5),
    "target": (float, 0.0, 0.99),
}
_SYNTHESIS_CHOICES = {
    "objective": ("residual", "follower_error", "acceleration"),
    "measure": ("rms", "peak"),
    "robust": ("worst", "average"),
    "start": ("program", "cycloidal", "modified_sine", "modified_trapezoid", "polynomial_4567"),
}


def synthesis_settings(table: Optional[Dict[str, Any]], *, path=None, contacts=None, dofs=None) -> Dict[str, Any]:
    """The keyword arguments of ``camfollower.synthesis.synthesize`` from a [synthesis] table (absent:
    the defaults), with ``start`` as a catalogue law's name or "program"; ``contacts`` and ``dofs``: the
    mechanism's, to check ``contact`` and ``output`` against."""
    table = {} if table is None else table
    if not isinstance(table, dict):
        raise ValueError(f"{_where(path, 'synthesis')}: must be a table, got {_a(table)}")
    _unknown(
        table,
        ("contact", "output", "rpm", "segments", "accuracy", *_SYNTHESIS_NUMBERS, *_SYNTHESIS_CHOICES),
        path,
        "synthesis",
    )
    out: Dict[str, Any] = {"contact": _contact(table, "synthesis.contact", path, contacts)}
    output = table.get("output")
    if output is not None and (not isinstance(output, str) or (dofs is not None and output not in dofs)):
        shown = _shown(output) if isinstance(output, str) else _a(output)
        raise ValueError(
            f"{_where(path, 'synthesis.output')}: must name a DOF of the mechanism, got {shown}"
            + (f"; its DOFs: {', '.join(_shown(d) for d in list(dofs)[:20])}" if dofs is not None else "")
        )
    out["output"] = output
    for key, choices in _SYNTHESIS_CHOICES.items():
        if key in table:
            v = table[key]
            if not isinstance(v, str) or v not in choices:
                got = _shown(v) if isinstance(v, str) else _a(v)
                raise ValueError(f"{_where(path, 'synthesis.' + key)}: must be one of {', '.join(choices)}, got {got}")
            out[key] = v
    for key, (kind, lo, hi) in _SYNTHESIS_NUMBERS.items():
        if key not in table:
            continue
        v = table[key]
        ok_type = isinstance(v, int) if kind is int else isinstance(v, (int, float))
        if isinstance(v, bool) or not ok_type or not (math.isfinite(v) or kind is int) or not lo <= v <= hi:
            what = "an integer" if kind is int else "a number"
            raise ValueError(f"{_where(path, 'synthesis.' + key)}: must be {what} in [{lo:g}, {hi:g}], got {_shown(v)}")
        if key in ("max_acceleration", "max_jerk", "min_radius", "max_output_acceleration", "max_stress") and v == 0:
            raise ValueError(f"{_where(path, 'synthesis.' + key)}: must be > 0, got 0")
        out[key] = kind(v)
    if ("max_stress" in out) != ("roller_width" in out):
        raise ValueError(
            f"{_where(path, 'synthesis.max_stress')}: max_stress (Pa) and roller_width (m) go together: the Hertz "
            "pressure needs the roller's width (steel on steel)"
        )
    if "roller_width" in out:
        if out["roller_width"] == 0:
            raise ValueError(f"{_where(path, 'synthesis.roller_width')}: must be > 0 (m), got 0")
        out["line_contact"] = _core.LineContact(out.pop("roller_width"))
    if "max_pressure_angle_deg" in out:
        out["max_pressure_angle"] = math.radians(out.pop("max_pressure_angle_deg"))
    if "band_speeds" in out:
        out["band_speeds_count"] = out.pop("band_speeds")
    if "rpm" in table:
        if "band" in table:
            raise ValueError(f"{_where(path, 'synthesis.rpm')}: give rpm (design speed first) or band, not both")
        speeds = table["rpm"]
        if not isinstance(speeds, list) or not speeds:
            raise ValueError(f"{_where(path, 'synthesis.rpm')}: must be a non-empty array of speeds (rpm)")
        out["speeds_rpm"] = [_speed(r, f"synthesis.rpm[{i}]", path) for i, r in enumerate(speeds)]
    if "segments" in table:
        seg = table["segments"]
        if not isinstance(seg, list) or not seg or not all(isinstance(i, int) and not isinstance(i, bool) for i in seg):
            raise ValueError(
                f"{_where(path, 'synthesis.segments')}: must be a non-empty array of segment indices (integers from 0)"
            )
        out["segments"] = seg
    accuracy = _accuracy(table, path, "synthesis")
    if accuracy is not None:
        out["accuracy"] = accuracy
    return out


__all__ = ["montecarlo_settings", "sweep_settings", "synthesis_settings"]
