# SPDX-License-Identifier: BSD-3-Clause
"""The design page's document: a config (``Config.data``) and the fields a designer edits in it.

Every field is a key path in the config, written as the library's messages write it
(``program.feed.segments[1].h``, ``contact[0].follower.base_radius``,
``preset.parameters.spring_stiffness``), so an error the reader or the model raises is shown at the
field it names. A value is typed as in a config file: a bare number is SI (rpm for the speed), or
``"<number> <unit>"`` (``12 mm``, ``30 N/mm``). Editing never changes anything but the key edited
(and, for a law or follower type, the keys that law or type needs); the library's reader checks it.
"""

from __future__ import annotations

import copy
import math
import re
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Tuple, Union

from .. import _core
from ..config import Config, config_from_dict, program_toml

Key = Union[str, int]

#: The catalogue laws a segment may take from a list (docs/config.md, "motion programs").
LAWS = (
    "dwell",
    "cycloidal",
    "modified_sine",
    "modified_trapezoid",
    "polynomial_345",
    "polynomial_4567",
    "simple_harmonic",
    "constant_acceleration",
    "sine_constant_cosine",
)
#: sine_constant_cosine's fractions when a segment is switched to it (the paper's).
SCC_FRACTIONS = {"b": 0.25, "c": 0.5, "d": 0.25}
#: Follower types that may replace each other: the lift keeps its meaning (a length or an arm angle).
SAME_MOTION = {
    "translating_roller": ("translating_roller", "translating_flat"),
    "translating_flat": ("translating_roller", "translating_flat"),
    "oscillating_roller": ("oscillating_roller", "oscillating_flat"),
    "oscillating_flat": ("oscillating_roller", "oscillating_flat"),
}
_FOLLOWER_KEYS = ("base_radius", "roller_radius", "offset", "face_angle", "arm_length", "face_offset", "pivot")
_CONTACT_KEYS = ("stiffness", "roller_width", "exponent", "damping_factor")
#: The paper preset's parameters the page offers, by group (docs/model.md has them all).
PAPER_FOLLOWER = ("base_radius", "roller_radius", "offset")
PAPER_LENGTHS = PAPER_FOLLOWER + ("spring_preload_deflection",)
PAPER_MECHANISM = (
    "spring_stiffness",
    "spring_preload_deflection",
    "follower_mass",
    "follower_rod_mass",
    "roller_mass",
    "camshaft_mass",
    "contact_stiffness",
    "rod_stiffness",
    "rod_damping",
    "guide_stiffness",
    "roller_pin_stiffness_vertical",
    "roller_pin_stiffness_horizontal",
    "bearing_stiffness_vertical",
    "bearing_stiffness_horizontal",
    "bearing_damping_vertical",
    "bearing_damping_horizontal",
)
_PAPER_UNITS = {
    "base_radius": "m",
    "roller_radius": "m",
    "offset": "m",
    "spring_preload_deflection": "m (preload = rate x this)",
    "mass": "kg",
    "stiffness": "N/m",
    "damping": "N s/m",
}
#: The default design: the paper's 7-DOF mechanism at its speed, its program written out to edit.
DEFAULT_DESIGN: Dict[str, Any] = {"camshaft": {"speed": 750.0}, "preset": {"name": "paper"}}


@dataclass(frozen=True)
class Field:
    """One editable (or shown) value: ``path`` (the key path), ``label``, ``value`` (as text),
    ``group`` (the panel it sits in), ``kind`` ("text", "choice" or "readonly"), ``choices`` and
    ``unit`` (what a bare number means)."""

    path: str
    label: str
    value: str
    group: str
    kind: str = "text"
    choices: Tuple[str, ...] = ()
    unit: str = ""


def split_path(path: str) -> List[Key]:
    """``"contact[0].follower.pivot[1]"`` -> ``["contact", 0, "follower", "pivot", 1]``."""
    keys: List[Key] = []
    for part in path.split("."):
        m = re.fullmatch(r"([^\[\]]+)((?:\[\d+\])*)", part)
        if not m:
            raise ValueError(f"field path {path!r}: cannot read {part!r}")
        keys.append(m[1])
        keys.extend(int(i) for i in re.findall(r"\[(\d+)\]", m[2]))
    return keys


def join_path(keys: List[Key]) -> str:
    text = ""
    for k in keys:
        text += f"[{k}]" if isinstance(k, int) else (f".{k}" if text else k)
    return text


def get(data: Dict[str, Any], path: str, default: Any = None) -> Any:
    node: Any = data
    for k in split_path(path):
        try:
            node = node[k]
        except (KeyError, IndexError, TypeError):
            return default
    return node


def shown(v: Any, unit: str = "") -> str:
    """A config value as the page shows it (what one would type into the file); a bare SI number of a
    length or angle in the page's ``unit`` ("mm" or "deg"), with that unit written."""
    if unit and isinstance(v, (int, float)) and not isinstance(v, bool):
        return f"{float(v) * (1e3 if unit == 'mm' else 180.0 / math.pi):.10g} {unit}"
    if isinstance(v, float):
        return f"{v:.12g}"
    if isinstance(v, (list, tuple)):
        return ", ".join(shown(x) for x in v)
    return "" if v is None else str(v)


def parse(text: Any) -> Union[float, str]:
    """A typed value: a bare number (SI) as float, anything else as the string the reader converts
    (``"12 mm"``); the reader refuses what it cannot read, naming the key."""
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return float(text)
    t = str(text).strip()
    try:
        return float(t)
    except ValueError:
        return t


def set_value(data: Dict[str, Any], path: str, text: Any) -> Dict[str, Any]:
    """A copy of `data` with the field at `path` set to `text` (typed as in a config file). An empty
    text removes an optional key (its default applies). A segment's law or a follower's type brings
    the keys it needs (and drops those it does not take); a segment's end lift carries the dwells after
    it along (they keep its level)."""
    out = copy.deepcopy(data)
    keys = split_path(path)
    node: Any = out
    for k in keys[:-1]:
        if isinstance(k, str) and isinstance(node, dict) and k not in node:
            node[k] = {}
        node = node[k]
    last = keys[-1]
    empty = text is None or str(text).strip() == ""
    if empty and not _optional(keys):
        raise ValueError(f"{path}: give a value (this key has no default)")
    if isinstance(last, int):  # an element of an array (a pivot's x or y)
        node[last] = parse(text)
        return out
    if last == "law":
        _set_law(out, keys, str(text))
    elif last == "type" and keys[-2] == "follower":
        _set_follower_type(node, str(text))
    elif empty:
        node.pop(last, None)
    else:
        old = node.get(last)
        node[last] = parse(text)
        if last == "h" and len(keys) >= 3 and keys[-3] == "segments":
            _dwells_follow(out, keys, old, node[last])
    return out


def _dwells_follow(data: Dict[str, Any], keys: List[Key], old: Any, new: Any) -> None:
    """The dwells right after a segment whose end lift changed from `old` to `new` keep its level: an
    explicit ``h`` there that held the old level takes the new one (a dwell's h must equal the level
    it starts at)."""
    segments = data
    for k in keys[:-2]:
        segments = segments[k]
    i = int(keys[-2])
    for seg in segments[i + 1 :]:
        if seg.get("law") != "dwell":
            break
        if "h" in seg and seg["h"] == old:
            seg["h"] = new


def _optional(keys: List[Key]) -> bool:
    """Keys an empty field may remove, their default then applying: the preset's parameters, a
    spring's preload and damping, a follower's offsets and face angle."""
    last = keys[-1]
    if keys[:2] == ["preset", "parameters"]:
        return True
    if keys[0] == "spring" and last in ("preload", "damping"):
        return True
    return len(keys) >= 2 and keys[-2] == "follower" and last in ("offset", "face_angle", "face_offset")


def _level_before(segments: List[Dict[str, Any]], i: int, program: Dict[str, Any]) -> Any:
    """The lift where segment `i` starts (as the file writes it): the last end lift before it."""
    for seg in reversed(segments[:i]):
        if "h" in seg:
            return seg["h"]
    return program.get("start_h", 0.0)


def _set_law(data: Dict[str, Any], keys: List[Key], law: str) -> None:
    """A segment's law; a dwell drops its lift (it keeps its level), a rise or return from a dwell
    starts with the level it had (its lift then to be typed), and the dwells after it follow."""
    if law not in LAWS:
        raise ValueError(f"law must be one of {', '.join(LAWS)}, got {law!r}")
    program = data
    for k in keys[:-3]:
        program = program[k]
    segments = program["segments"]
    i = int(keys[-2])
    segment = segments[i]
    old, old_h = segment.get("law"), segment.get("h")
    segment["law"] = law
    for k in ("b", "c", "d"):
        if law != "sine_constant_cosine":
            segment.pop(k, None)
        else:
            segment.setdefault(k, SCC_FRACTIONS[k])
    if old == "polynomial":
        for k in ("start_derivatives", "end_derivatives", "interior_theta", "interior_h"):
            segment.pop(k, None)
    level = _level_before(segments, i, program)
    if law == "dwell":
        segment.pop("h", None)  # a dwell keeps the level it starts at
        if old_h is not None:
            _dwells_follow(data, keys[:-1] + ["h"], old_h, level)
    elif "h" not in segment:
        segment["h"] = level


def _metres(value: Any) -> Optional[float]:
    """A length as the config writes it (a bare number in m, or "<number> <length unit>") in m."""
    v = parse(value) if value is not None else None
    if isinstance(v, float):
        return v
    if isinstance(v, str):
        number, _, unit = v.partition(" ")
        factor = _core.length_units().get(unit.strip())
        try:
            return float(number) * factor if factor else None
        except ValueError:
            return None
    return None


def _set_follower_type(follower: Dict[str, Any], kind: str) -> None:
    old = follower.get("type")
    allowed = SAME_MOTION.get(old, (old,))
    if kind not in allowed:
        raise ValueError(f"type: a {old} follower may become one of {', '.join(allowed)} (the lift keeps its meaning)")
    follower["type"] = kind
    base = _metres(follower.get("base_radius")) or 0.04
    if kind.endswith("_flat"):
        for k in ("roller_radius", "arm_length"):
            follower.pop(k, None)
    if kind.endswith("_roller"):  # a roller a quarter of the base radius: a start to edit
        follower.pop("face_angle", None)
        follower.pop("face_offset", None)
        follower.setdefault("roller_radius", 0.25 * base)
    if kind == "oscillating_roller":  # the arm reaching the cam centre from the pivot: a start to edit
        pivot = [_metres(x) for x in follower.get("pivot", [])]
        if len(pivot) == 2 and None not in pivot:
            follower.setdefault("arm_length", math.hypot(*pivot))


# ---------------------------------------------------------------------------------------------------
# The document's contacts and programs


def contact_names(case: Config) -> List[str]:
    return [c["name"] for c in case.builder.contacts]


def _data_contact(data: Dict[str, Any], name: str) -> Optional[int]:
    """The index in ``data["contact"]`` of the built contact `name` (conjugate cams build two contacts,
    ``<name>.lift`` and ``<name>.return``, from one table)."""
    for i, c in enumerate(data.get("contact", []) or []):
        if c.get("name") == name or name.startswith(f"{c.get('name')}."):
            return i
    return None


def program_name(data: Dict[str, Any], contact: str) -> Optional[str]:
    """The name of the program the contact (or the paper preset) uses in `data`."""
    if "preset" in data:
        return data["preset"].get("program")
    i = _data_contact(data, contact)
    return None if i is None else data["contact"][i].get("program")


def with_program(data: Dict[str, Any], name: str, program, rotary: bool = False) -> Dict[str, Any]:
    """A copy of `data` whose ``[program.<name>]`` is `program` (a MotionProgram), as the config table
    that loads back exactly (config.program_toml); ``rotary``: an arm's lift, in rad."""
    out = copy.deepcopy(data)
    text = program_toml(program, name, rotary=rotary)
    out.setdefault("program", {})[name] = _core._parse_toml(text.encode(), "<program>")["program"][name]
    return out


def with_program_written_out(data: Dict[str, Any], case: Config) -> Dict[str, Any]:
    """The paper preset without a ``program`` of its own uses the paper's lift: written out as a
    ``[program.paper]`` table (the same program, exactly) so that its segments can be edited."""
    preset = data.get("preset")
    if not preset or preset.get("name") not in ("paper", "paper_damped") or preset.get("program"):
        return data
    name = "paper"
    while name in data.get("program", {}):
        name += "_"
    out = with_program(data, name, case.builder.contacts[0]["program"])
    out["preset"]["program"] = name
    return out


def fields(data: Dict[str, Any], case: Config, contact: str) -> List[Field]:
    """The fields of the page for `data` (built as `case`), showing the contact named `contact`."""
    out = [Field("camshaft.speed", "camshaft speed", shown(get(data, "camshaft.speed")), "Camshaft", unit="rpm")]
    out += _program_fields(data, contact)
    if "preset" in data:
        out += _preset_fields(data, case)
    else:
        out += _part_fields(data, contact)
    return out


def _program_fields(data: Dict[str, Any], contact: str) -> List[Field]:
    name = program_name(data, contact)
    program = get(data, f"program.{name}") if name else None
    group = f"Motion program '{name}'" if name else "Motion program"
    if not isinstance(program, dict):
        return [Field("program", "program", "the preset's own (not editable here)", group, "readonly")]
    segments = program.get("segments")
    if not isinstance(segments, list):
        n = len(program.get("theta", []) or [])
        what = f"file {program['file']}" if "file" in program else f"{n} points"
        return [Field(f"program.{name}", "whole-revolution lift table", what, group, "readonly")]
    rows: List[Field] = []
    lift = "mm" if translating(data, contact) else "deg"
    for i, s in enumerate(segments):
        base = f"program.{name}.segments[{i}]"
        law = s.get("law", "")
        if law == "table":
            n = len(s.get("theta", []) or [])
            what = f"file {s['file']}" if "file" in s else f"{n} points"
            rows.append(Field(f"{base}.law", f"segment {i + 1}", f"lift table ({what})", group, "readonly"))
            continue
        if law == "polynomial":
            rows.append(Field(f"{base}.law", f"segment {i + 1}", "polynomial", group, "choice", LAWS + ("polynomial",)))
        else:
            rows.append(Field(f"{base}.law", f"segment {i + 1}", law, group, "choice", LAWS))
        rows.append(Field(f"{base}.end", "  ends at", shown(s.get("end"), "deg"), group, unit="rad, or '150 deg'"))
        if law != "dwell":
            rows.append(Field(f"{base}.h", "  lift at its end", shown(s.get("h"), lift), group, unit=_LIFT_UNITS[lift]))
        if law == "sine_constant_cosine":
            for k in ("b", "c", "d"):
                rows.append(Field(f"{base}.{k}", f"  fraction {k}", shown(s.get(k)), group))
    return rows


_LIFT_UNITS = {"mm": "m, or '12 mm'", "deg": "rad, or '15 deg'"}


def translating(data: Dict[str, Any], contact: str) -> bool:
    if "preset" in data:
        return True
    i = _data_contact(data, contact)
    kind = str(get(data, f"contact[{i}].follower.type", "")) if i is not None else ""
    return not kind.startswith("oscillating") and kind != "barrel_arm_roller"


def _preset_fields(data: Dict[str, Any], case: Config) -> List[Field]:
    preset = data["preset"]
    if preset.get("name") not in ("paper", "paper_damped"):
        params = preset.get("parameters", {}) or {}
        return [
            Field(f"preset.parameters.{k}", k.replace("_", " "), shown(v), "Mechanism")
            for k, v in params.items()
            if isinstance(v, (int, float, str)) and not isinstance(v, bool)
        ]
    defaults = _core.Parameters()
    given = preset.get("parameters", {}) or {}
    out = [Field("preset.name", "follower", "translating roller (paper preset)", "Follower", "readonly")]

    def row(name: str, group: str) -> Field:
        unit = next((u for k, u in _PAPER_UNITS.items() if name == k or name.endswith(k)), "")
        return Field(
            f"preset.parameters.{name}",
            name.replace("_", " "),
            shown(given.get(name, float(getattr(defaults, name))), "mm" if name in PAPER_LENGTHS else ""),
            group,
            unit=unit,
        )

    out += [row(n, "Follower") for n in PAPER_FOLLOWER]
    out += [row(n, "Mechanism") for n in PAPER_MECHANISM]
    return out


def _part_fields(data: Dict[str, Any], contact: str) -> List[Field]:
    out: List[Field] = []
    i = _data_contact(data, contact)
    if i is not None:
        c = data["contact"][i]
        base = f"contact[{i}]"
        group = f"Follower (contact '{c.get('name')}')"
        f = c.get("follower", {}) or {}
        kind = f.get("type", "")
        out.append(Field(f"{base}.follower.type", "type", kind, group, "choice", SAME_MOTION.get(kind, (kind,))))
        for k in _FOLLOWER_KEYS:
            if k not in f:
                continue
            if k == "pivot":
                for j, axis in enumerate(("x", "y")):
                    out.append(
                        Field(f"{base}.follower.pivot[{j}]", f"pivot {axis}", shown(f[k][j], "mm"), group, unit="m")
                    )
            elif k == "face_angle":
                out.append(Field(f"{base}.follower.{k}", "face angle", shown(f[k], "deg"), group, unit="rad"))
            else:
                out.append(Field(f"{base}.follower.{k}", k.replace("_", " "), shown(f[k], "mm"), group, unit="m"))
        for k in _CONTACT_KEYS:
            if k in c:
                out.append(Field(f"{base}.{k}", f"contact {k.replace('_', ' ')}", shown(c[k]), group))
    for j, d in enumerate(data.get("dof", []) or []):
        out.append(Field(f"dof[{j}].mass", f"mass of '{d.get('name')}'", shown(d.get("mass")), "Mechanism", unit="kg"))
    for j, s in enumerate(data.get("spring", []) or []):
        n = s.get("name", j)
        for k, unit in (("stiffness", "N/m"), ("preload", "N"), ("damping", "N s/m")):
            out.append(Field(f"spring[{j}].{k}", f"spring '{n}' {k}", shown(s.get(k, 0.0)), "Mechanism", unit=unit))
    for j, s in enumerate(data.get("damper", []) or []):
        out.append(
            Field(
                f"damper[{j}].damping",
                f"damper '{s.get('name', j)}'",
                shown(s.get("damping")),
                "Mechanism",
                unit="N s/m",
            )
        )
    return out


def build(data: Dict[str, Any], base_dir: str) -> Config:
    """The case `data` describes (the library's reader: its errors name the key path)."""
    return config_from_dict(data, base_dir)


#: A table's message that names no key of it: the field whose change is the usual remedy.
_REMEDIES = (("pressure angle", "base_radius"), ("cusp", "base_radius"))


def field_of_message(message: str, paths: List[str]) -> Optional[str]:
    """The field an error message is about: the longest field path the message names (``<dict>:
    contact[0].follower.base_radius: ...``); a message about a whole table (``contact[0]: ... the cam
    profile undercuts ... must exceed roller_radius``) goes to the field of that table whose key it
    names first, a segment that does not fit (``segments[2] spans ...``) to where it ends, a pressure
    angle reaching 90 deg or a cusp to the base radius, else to the table's first field."""
    m = re.match(r"(?:<dict>: )?([A-Za-z0-9_.\[\]-]+): ", message)
    named = m[1] if m else ""
    hits = [p for p in paths if named == p or named.startswith(p + ".") or named.startswith(p + "[")]
    if hits:
        return max(hits, key=len)
    inside = [p for p in paths if named and (p.startswith(named + ".") or p.startswith(named + "["))]
    rest = message[len(m[0]) if m else 0 :]
    found = []
    for p in inside:  # the key the message names first ("must exceed roller_radius ... enlarge base_radius")
        hit = re.search(rf"\b{re.escape(str(split_path(p)[-1]))}\b", rest)
        if hit:
            found.append((hit.start(), p))
    if found:
        return min(found)[1]
    segment = re.search(r"\bsegments\[(\d+)\]", rest)
    if segment and f"{named}[{segment[1]}].end" in paths:  # a segment that does not fit: where it ends
        return f"{named}[{segment[1]}].end"
    for phrase, key in _REMEDIES:
        if phrase in rest:
            for p in inside:
                if p.endswith(f".{key}"):
                    return p
    if inside:
        return inside[0]
    if named.startswith("program.") or named.startswith("preset.program"):
        prog = [p for p in paths if p.startswith("program.")]
        return prog[0] if prog else None
    # No key path (a profile check's message): the follower's geometry key it names first.
    named_keys = []
    for p in paths:
        key = str(split_path(p)[-1])
        hit = re.search(rf"\b{re.escape(key)}\b", message) if key in _FOLLOWER_KEYS + PAPER_FOLLOWER else None
        if hit:
            named_keys.append((hit.start(), p))
    return min(named_keys)[1] if named_keys else None


__all__ = [
    "DEFAULT_DESIGN",
    "Field",
    "LAWS",
    "build",
    "contact_names",
    "field_of_message",
    "fields",
    "get",
    "parse",
    "program_name",
    "set_value",
    "shown",
    "split_path",
    "translating",
    "with_program",
    "with_program_written_out",
]
