# SPDX-License-Identifier: BSD-3-Clause
"""Electronic cams: a motion program as the tables that servo controllers take (docs/ecam.md).

A packaging machine's servo axis follows a *master* (a real or virtual axis) through a motion law
given as a table. Here one master cycle is one cam revolution: master position 0 .. ``master_period``
(in ``master_unit``) is cam angle theta = 0 .. 2 pi, theta = 2 pi master / master_period. The slave
is the follower's lift h: a length (m, mm, um) for a translating follower, an angle (rad, deg) for an
oscillating one (``rotary=True``; the program's lift is then in rad).

Three formats, each with its reader:

- **Equidistant master/slave table (CSV)**, :func:`write_table_csv`: ``points`` equal master steps,
  columns master, slave, d(slave)/d(master), d2(slave)/d(master)2 (per master unit, not per second),
  and with a ``speed_rpm`` also time and the per-second velocity and acceleration. Closed by
  default: a last row at master = master_period repeats the first. The commented header states the
  units, the master period, the point count and how the derivatives are defined.
  :func:`read_table_csv` gives the columns and those facts back; :func:`program_from_table_csv` fits
  them with ``MotionProgram.from_table`` (a periodic B-spline, degree 5 by default).
- **Segment list (VDI 2143 style)**, :func:`write_segment_list`: one row per segment, master and
  slave at its ends, the catalogue law by name (``camfollower.MotionLaw.<name>()``; VDI 2143's
  German names in docs/ecam.md) and the boundary velocity and acceleration. Only for programs made of
  catalogue laws: a spline or polynomial segment (``law.is_custom``) is refused, named by index.
  :func:`read_segment_list` rebuilds the same program (bit for bit in rad and m; in other units
  to within one unit in the last place of the conversion).
- **TwinCAT CNC / ISG MC platform cam table** (the "ASCII interpreter" file of the MC platform's
  PLCopen cam functions), :func:`write_twincat_cnc_table`, as documented by Beckhoff:
  https://infosys.beckhoff.com/content/1033/tccncmcplatform_fb/15306147467.html (file format, and
  its sub-pages: header, table data, table types, function types, tokens and separators, comments)
  and https://infosys.beckhoff.com/content/1033/tccncmcplatform_fb/15306123915.html (interpolation
  point tables). A header (``Tablename``, ``Tabletype = 3`` = TABLE_ONE_COLUMN_REAL64, ``Table-ID``,
  ``Functiontype``, ``Lines``), then ``Begintable``, one slave position a line, ``EndTable``. The
  lines are equidistant interpolation points over the master's modulo range 0 .. 360 deg (the file
  holds no master positions); the slave in the MC platform's unit, 1E-4 mm (0.1 um) or 1E-4 deg.
  :func:`read_twincat_cnc_table` and :func:`program_from_twincat_cnc_table` read such a file back.

Every file is written atomically through ``camfollower._files`` (a temporary, then a rename).
Bad arguments raise ValueError naming the parameter and its allowed values or range.

>>> import camfollower as cf
>>> from camfollower import ecam
>>> t = ecam.cam_table(cf.MotionProgram.paper_default(), points=360)
>>> t["columns"][:2], len(t["master"]), float(t["master"][-1])
(['master_deg', 'slave_mm'], 361, 360.0)
>>> round(float(t["slave"][180]), 9)      # the paper's 10 mm rise is complete at 180 deg
10.0
"""

from __future__ import annotations

import math
import numbers
import re
from pathlib import Path
from typing import Optional

import numpy as np

from . import _core, _files
from ._core import MotionLaw, MotionProgram, Segment

__all__ = [
    "cam_table",
    "write_table_csv",
    "read_table_csv",
    "program_from_table_csv",
    "segment_list",
    "write_segment_list",
    "read_segment_list",
    "write_twincat_cnc_table",
    "read_twincat_cnc_table",
    "program_from_twincat_cnc_table",
    "MIN_POINTS",
    "MAX_POINTS",
    "TWINCAT_CNC_SOURCE",
]

TWO_PI = 2.0 * math.pi
MIN_POINTS = 8
MAX_POINTS = 1_000_000

# Slave units: SI units (m or rad) per unit.
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6}
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}
# Master units: a rotary master (one cam revolution is 360 deg or 2 pi rad unless master_period says
# otherwise) or a linear one (a conveyor: master_period is then required).
MASTER_UNITS = ("deg", "rad", "m", "mm", "um")
_DEFAULT_PERIOD = {"deg": 360.0, "rad": TWO_PI}

TABLE_FORMAT = "camfollower-ecam-table/1"
SEGMENT_FORMAT = "camfollower-ecam-segments/1"

# Catalogue laws by the name MotionLaw.<name>().name reports; the sine-constant-cosine family
# reports its parameters, two of its members have names of their own.
CATALOGUE_LAWS = (
    "dwell",
    "constant_acceleration",
    "simple_harmonic",
    "cycloidal",
    "polynomial_345",
    "polynomial_4567",
    "modified_sine",
    "modified_trapezoid",
    "sine_constant_cosine",
)
_NAMED_SCC = {(0.25, 0.0, 0.75): "modified_sine", (0.25, 0.5, 0.25): "modified_trapezoid"}

TWINCAT_CNC_SOURCE = "https://infosys.beckhoff.com/content/1033/tccncmcplatform_fb/15306147467.html"
TWINCAT_CNC_POINT_TABLES = "https://infosys.beckhoff.com/content/1033/tccncmcplatform_fb/15306123915.html"
# Table types of the ASCII interpreter (Beckhoff, "Table types"): the one-column ones are the
# equidistant interpolation point tables this module writes (3) and reads (1, 2, 3).
_TWINCAT_TABLE_TYPES = {
    1: "TABLE_ONE_COLUMN_SGN16",
    2: "TABLE_ONE_COLUMN_SGN32",
    3: "TABLE_ONE_COLUMN_REAL64",
    4: "TABLE_4_COLUMNS_SGN32",
    5: "TABLE_4_COLUMN_REAL64",
    6: "TABLE_MOTION_PATTERNS",
    7: "TABLE_TWO_COLUMNS_SGN32",
}
# Function (interpolation) types (Beckhoff, "Function types"); 0-2 apply to interpolation point tables.
_TWINCAT_FUNCTION_TYPES = {
    0: "STEP_DIRECT",
    1: "LINEAR",
    2: "POLYNOM_3",
    3: "POLYNOM_3_KOEFF",
    4: "LINE_POLY5",
    5: "POLY5_LINE",
    6: "TABLE_DEFINED",
}
# The MC platform's position unit, 1E-4 mm or 1E-4 deg: file units per m, per rad.
_TWINCAT_PER_M = 1e7
_TWINCAT_PER_RAD = 1e4 * 180.0 / math.pi


# --------------------------------------------------------------------------------------------------
# Checks shared by the writers


def _check_program(program) -> None:
    if not isinstance(program, MotionProgram):
        raise ValueError(f"program must be a camfollower.MotionProgram, got {type(program).__name__}")


def _check_points(points) -> int:
    if isinstance(points, bool) or not isinstance(points, numbers.Integral) or not MIN_POINTS <= points <= MAX_POINTS:
        raise ValueError(f"points must be an integer in [{MIN_POINTS}, {MAX_POINTS}], got {points!r}")
    return int(points)


def _check_slave_unit(slave_unit, rotary) -> float:
    if not isinstance(rotary, bool):
        raise ValueError(f"rotary must be True (oscillating follower, lift in rad) or False, got {rotary!r}")
    allowed = ANGLE_UNITS if rotary else LENGTH_UNITS
    if not isinstance(slave_unit, str) or slave_unit not in allowed:
        kind = "an oscillating follower (rotary=True)" if rotary else "a translating follower (rotary=False)"
        raise ValueError(
            f"slave_unit must be one of {', '.join(repr(u) for u in allowed)} for {kind}, got {slave_unit!r}"
        )
    return allowed[slave_unit]


def _check_master(master_unit, master_period) -> float:
    if not isinstance(master_unit, str) or master_unit not in MASTER_UNITS:
        raise ValueError(f"master_unit must be one of {', '.join(repr(u) for u in MASTER_UNITS)}, got {master_unit!r}")
    if master_period is None:
        if master_unit not in _DEFAULT_PERIOD:
            raise ValueError(
                f"master_period is required for a linear master (master_unit={master_unit!r}): the master's "
                f"travel per cam revolution, a finite number > 0 in {master_unit}"
            )
        return _DEFAULT_PERIOD[master_unit]
    if (
        isinstance(master_period, bool)
        or not isinstance(master_period, numbers.Real)
        or not math.isfinite(master_period)
        or not master_period > 0
    ):
        raise ValueError(
            f"master_period must be a finite number > 0 ({master_unit} of master travel per cam revolution), "
            f"got {master_period!r}"
        )
    return float(master_period)


def _check_speed(speed_rpm) -> Optional[float]:
    if speed_rpm is None:
        return None
    lo, hi = _core.MIN_CAMSHAFT_SPEED * 30.0 / math.pi, _core.MAX_CAMSHAFT_SPEED * 30.0 / math.pi
    if (
        isinstance(speed_rpm, bool)
        or not isinstance(speed_rpm, numbers.Real)
        or not math.isfinite(speed_rpm)
        or not lo <= speed_rpm <= hi
    ):
        raise ValueError(f"speed_rpm must be None or a number in [{lo:g}, {hi:g}] (cam rpm), got {speed_rpm!r}")
    return float(speed_rpm)


def _g(x: float) -> str:
    """A float as the shortest text that reads back to the same float (-0 as 0)."""
    return repr(float(x) + 0.0)


def _g_si(value: float, to_si: float, si: float) -> str:
    """``value`` (= si / to_si) as the shortest decimal that a reader multiplying it by ``to_si`` turns
    back into ``si`` bit for bit (30.0 rather than 29.999999999999996 for pi/6 rad in deg), looking at
    ``value`` and its neighbouring floats; the shortest exact decimal of ``value`` when none does."""
    candidates = [float(value)]
    up = down = float(value)
    for _ in range(4):
        up, down = math.nextafter(up, math.inf), math.nextafter(down, -math.inf)
        candidates += [up, down]
    for c in candidates:
        if c * to_si == si:
            for digits in (15, 16):
                text = f"{c:.{digits}g}"
                if float(text) * to_si == si:
                    return text if any(ch in text for ch in ".en") else text + ".0"
            return _g(c)
    return _g(value)


def _program_summary(program: MotionProgram, slave_unit: str, factor: float) -> str:
    segs = program.segments
    parts = []
    for s in segs[:12]:
        parts.append(
            f"{s.law.name} {math.degrees(s.theta_start):.10g}-{math.degrees(s.theta_end):.10g} deg, "
            f"{s.h_start / factor:.10g} -> {s.h_end / factor:.10g} {slave_unit}"
        )
    more = f"; ... ({len(segs) - 12} more)" if len(segs) > 12 else ""
    return f"{len(segs)} segment{'s' if len(segs) != 1 else ''}: " + "; ".join(parts) + more


def _read_text(path, parameter: str = "path") -> tuple:
    name = _files.check_name(path, parameter)
    raw = Path(name).read_bytes()
    try:
        return name, raw.decode("utf-8")
    except UnicodeDecodeError:  # an ANSI file from a Windows tool (the manual's own "Sinus_360°")
        return name, raw.decode("latin-1")


def _header_facts(lines) -> dict:
    """The ``# key: value`` lines of a commented header as {key: value text}."""
    facts = {}
    for line in lines:
        m = re.match(r"#\s*([A-Za-z_]+)\s*:\s*(.*)$", line)
        if m and m.group(1) not in facts:
            facts[m.group(1)] = m.group(2).strip()
    return facts


def _first_number(facts: dict, key: str, where: str) -> float:
    text = facts.get(key)
    if text is None:
        raise ValueError(f"{where}: the header has no '# {key}:' line")
    try:
        value = float(text.split()[0])
    except (ValueError, IndexError):
        raise ValueError(f"{where}: '# {key}: {text}' does not start with a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{where}: '# {key}: {text}' is not finite")
    return value


def _first_word(facts: dict, key: str, where: str) -> str:
    text = facts.get(key)
    if not text:
        raise ValueError(f"{where}: the header has no '# {key}:' line")
    return text.split()[0]


# --------------------------------------------------------------------------------------------------
# 1. The equidistant master/slave table


def cam_table(
    program: MotionProgram,
    *,
    points: int = 360,
    master_period: Optional[float] = None,
    master_unit: str = "deg",
    slave_unit: str = "mm",
    rotary: bool = False,
    closed: bool = True,
    speed_rpm: Optional[float] = None,
) -> dict:
    """The equidistant table as numpy arrays (what :func:`write_table_csv` writes).

    ``master`` = master_period k / points (k = 0 .. points - 1, and k = points when ``closed``: that
    row repeats the first), ``slave`` (lift in ``slave_unit``), ``slave_velocity`` =
    d(slave)/d(master) (slave_unit per master_unit), ``slave_acceleration`` = d2(slave)/d(master)2
    (slave_unit per master_unit^2); with ``speed_rpm`` (cam revolutions per minute) also ``time``
    (s), ``slave_velocity_time`` (slave_unit/s) and ``slave_acceleration_time`` (slave_unit/s^2).
    Also ``theta`` (rad), the facts (``points``, ``master_period``, ``master_unit``, ``slave_unit``,
    ``rotary``, ``closed``, ``speed_rpm``), ``columns`` (the CSV column names, in the order of the
    arrays) and ``notes`` (the CSV header lines). ``master_period`` defaults to one turn of a rotary
    master (360 deg, 2 pi rad) and is required for a linear one (m, mm, um). The lift comes from
    ``program.evaluate``, a manufacturing error the program carries included."""
    _check_program(program)
    points = _check_points(points)
    period = _check_master(master_unit, master_period)
    factor = _check_slave_unit(slave_unit, rotary)
    speed = _check_speed(speed_rpm)
    if not isinstance(closed, bool):
        raise ValueError(f"closed must be True (a last row at master = master_period) or False, got {closed!r}")

    k = np.arange(points, dtype=float)
    theta = TWO_PI * k / points
    lift = program.evaluate(theta)
    rate = TWO_PI / period  # dtheta/dmaster, rad per master unit
    master = period * k / points
    slave = np.asarray(lift["h"], dtype=float) / factor
    velocity = np.asarray(lift["dh"], dtype=float) * rate / factor
    acceleration = np.asarray(lift["d2h"], dtype=float) * rate**2 / factor
    if closed:  # the cam closes over a revolution: the row at master = period is the first one again
        theta = np.append(theta, TWO_PI)
        master = np.append(master, period)
        slave, velocity, acceleration = (np.append(a, a[0]) for a in (slave, velocity, acceleration))
    mu, su = master_unit, slave_unit
    out = {
        "master": master,
        "slave": slave,
        "slave_velocity": velocity,
        "slave_acceleration": acceleration,
        "theta": theta,
        "columns": [
            f"master_{mu}",
            f"slave_{su}",
            f"slave_velocity_{su}_per_{mu}",
            f"slave_acceleration_{su}_per_{mu}2",
        ],
    }
    if speed is not None:
        omega = speed * TWO_PI / 60.0
        out["time"] = theta / omega
        out["slave_velocity_time"] = np.asarray(lift["dh"], dtype=float) * omega / factor
        out["slave_acceleration_time"] = np.asarray(lift["d2h"], dtype=float) * omega**2 / factor
        if closed:
            for key in ("slave_velocity_time", "slave_acceleration_time"):
                out[key] = np.append(out[key], out[key][0])
        out["columns"] += ["time_s", f"slave_velocity_{su}_per_s", f"slave_acceleration_{su}_per_s2"]

    si = "m" if not rotary else "rad"
    rows = points + 1 if closed else points
    notes = [
        "camfollower electronic cam table: equidistant master/slave points over one master cycle",
        f"format: {TABLE_FORMAT}",
        f"master_unit: {mu}",
        f"master_period: {_g(period)} ({mu} of master travel per cycle)",
        "cycle: one master cycle (master 0 .. master_period) is one cam revolution (2 pi rad of cam angle); "
        "theta = 2 pi master / master_period",
        f"points: {points} (equidistant master steps of master_period / points = {_g(period / points)} {mu})",
        f"closed: {'yes' if closed else 'no'} ("
        + (
            f"{rows} rows: the last, at master = master_period, repeats the first)"
            if closed
            else f"{rows} rows, master 0 .. master_period - step; the cycle repeats after the last)"
        ),
        f"slave_kind: {'rotary (oscillating follower)' if rotary else 'translating'}",
        f"slave_unit: {su} (1 {su} = {_g(factor)} {si})",
        f"velocity: slave_velocity = d(slave)/d(master) in {su}/{mu}: a derivative with respect to the master "
        "position, not time",
        f"acceleration: slave_acceleration = d2(slave)/d(master)2 in {su}/{mu}^2",
    ]
    if speed is None:
        notes.append("speed_rpm: none (no time columns: they need a speed)")
    else:
        notes.append(
            f"speed_rpm: {_g(speed)} (cam revolutions per minute; one master cycle takes {_g(60.0 / speed)} s: "
            f"time_s = theta / omega, slave_velocity_{su}_per_s = d(slave)/dt, "
            f"slave_acceleration_{su}_per_s2 = d2(slave)/dt2 at that constant speed)"
        )
    notes.append(f"program: {_program_summary(program, su, factor)}")
    if program.profile_error is not None:
        notes.append("profile_error: included (the program carries a manufacturing error; the slave follows it)")
    out.update(
        points=points,
        master_period=period,
        master_unit=mu,
        slave_unit=su,
        rotary=rotary,
        closed=closed,
        speed_rpm=speed,
        notes=notes,
    )
    return out


def write_table_csv(
    path,
    program: MotionProgram,
    *,
    points: int = 360,
    master_period: Optional[float] = None,
    master_unit: str = "deg",
    slave_unit: str = "mm",
    rotary: bool = False,
    closed: bool = True,
    speed_rpm: Optional[float] = None,
) -> Path:
    """Write the equidistant master/slave table as CSV: ``# `` header lines stating the units, the
    master period, the point count and how velocity and acceleration are defined, a line of column
    names, then one row per master position (shortest exact decimal of each float). The arguments
    are :func:`cam_table`'s. ``points`` in [8, 1e6]; ``master_unit`` deg, rad, m, mm or um;
    ``slave_unit`` m, mm or um, or with ``rotary=True`` rad or deg. Returns the path."""
    table = cam_table(
        program,
        points=points,
        master_period=master_period,
        master_unit=master_unit,
        slave_unit=slave_unit,
        rotary=rotary,
        closed=closed,
        speed_rpm=speed_rpm,
    )
    keys = ["master", "slave", "slave_velocity", "slave_acceleration"]
    if table["speed_rpm"] is not None:
        keys += ["time", "slave_velocity_time", "slave_acceleration_time"]
    columns = np.column_stack([table[k] for k in keys]) + 0.0  # + 0.0: no "-0.0"
    lines = [f"# {note}" for note in table["notes"]]
    lines.append(f"# columns: {','.join(table['columns'])}")
    lines.append(",".join(table["columns"]))
    lines.extend(",".join(map(repr, row)) for row in columns.tolist())
    return _files.write_text(path, "\n".join(lines) + "\n")


def _read_units(path, reader: str, fmt: str, what: str):
    """The parts of a camfollower file every reader needs: (header lines, body lines, header facts, the
    message prefix, master unit, master period, slave unit, rotary, slave unit in SI per unit), the
    format line and the units checked."""
    name, text = _read_text(path)
    lines = text.splitlines()
    header = [ln for ln in lines if ln.startswith("#")]
    body = [ln for ln in lines if ln.strip() and not ln.startswith("#")]
    where = f"{reader}: {name!r}"
    facts = _header_facts(header)
    if facts.get("format", "").split()[:1] != [fmt]:
        raise ValueError(f"{where} is not a camfollower {what} (no '# format: {fmt}' line)")
    mu = _first_word(facts, "master_unit", where)
    period = _first_number(facts, "master_period", where)
    su = _first_word(facts, "slave_unit", where)
    rotary = _first_word(facts, "slave_kind", where) == "rotary"
    try:
        period = _check_master(mu, period)
        factor = _check_slave_unit(su, rotary)
    except ValueError as e:
        raise ValueError(f"{where}: {e}") from None
    return header, body, facts, where, mu, period, su, rotary, factor


def read_table_csv(path) -> dict:
    """Read a table written by :func:`write_table_csv`: the arrays (``master``, ``slave``,
    ``slave_velocity``, ``slave_acceleration``, and ``time``, ``slave_velocity_time``,
    ``slave_acceleration_time`` when the file has them), the header facts (``points``,
    ``master_period``, ``master_unit``, ``slave_unit``, ``rotary``, ``closed``, ``speed_rpm``),
    ``columns``, ``header`` (the comment lines) and in SI units ``theta`` (rad) and ``h`` (m, or rad
    for a rotary slave). Raises ValueError naming the file and what is wrong with it."""
    header, body, facts, where, mu, period, su, rotary, factor = _read_units(
        path, "read_table_csv", TABLE_FORMAT, "electronic cam table"
    )
    points = _first_number(facts, "points", where)
    if points != int(points) or not MIN_POINTS <= points <= MAX_POINTS:
        raise ValueError(f"{where}: points must be an integer in [{MIN_POINTS}, {MAX_POINTS}], got {points:g}")
    points = int(points)
    closed = _first_word(facts, "closed", where) == "yes"
    speed_rpm = None if facts.get("speed_rpm", "none").startswith("none") else _first_number(facts, "speed_rpm", where)
    expected = [f"master_{mu}", f"slave_{su}", f"slave_velocity_{su}_per_{mu}", f"slave_acceleration_{su}_per_{mu}2"]
    if speed_rpm is not None:
        expected += ["time_s", f"slave_velocity_{su}_per_s", f"slave_acceleration_{su}_per_s2"]
    if not body or body[0].split(",") != expected:
        got = body[0] if body else "nothing"
        raise ValueError(f"{where}: expected the column line {','.join(expected)!r}, got {got!r}")
    rows = points + 1 if closed else points
    if len(body) - 1 != rows:
        raise ValueError(
            f"{where}: the header says {rows} rows (points {points}, closed: {closed}), got {len(body) - 1}"
        )
    try:
        data = np.loadtxt(body[1:], delimiter=",", dtype=float, ndmin=2)
    except ValueError as e:
        raise ValueError(f"{where}: a row is not {len(expected)} comma-separated numbers ({e})") from None
    if data.shape != (rows, len(expected)) or not np.all(np.isfinite(data)):
        raise ValueError(f"{where}: every row must hold {len(expected)} finite numbers")
    master = data[:, 0]
    step = period / points
    if np.max(np.abs(master - step * np.arange(rows))) > 1e-9 * period:
        raise ValueError(f"{where}: the master column is not master_period k / points (k = 0 .. {rows - 1})")
    keys = ["master", "slave", "slave_velocity", "slave_acceleration"]
    if speed_rpm is not None:
        keys += ["time", "slave_velocity_time", "slave_acceleration_time"]
    out = {k: data[:, i].copy() for i, k in enumerate(keys)}
    out.update(
        points=points,
        master_period=period,
        master_unit=mu,
        slave_unit=su,
        rotary=rotary,
        closed=closed,
        speed_rpm=speed_rpm,
        columns=expected,
        header=header,
        theta=TWO_PI * master / period,
        h=out["slave"] * factor,
    )
    return out


def program_from_table_csv(path, *, degree: int = 5, smoothing: float = 0.0) -> MotionProgram:
    """The program through a table written by :func:`write_table_csv`:
    ``MotionProgram.from_table(theta, h, degree, smoothing)`` over its ``points`` rows (a closed
    table's repeated last row left out). An interpolating periodic B-spline (``smoothing = 0``) of odd
    ``degree`` (1, 3, 5, 7); its accuracy: docs/ecam.md."""
    table = read_table_csv(path)
    n = table["points"]
    return MotionProgram.from_table(table["theta"][:n], table["h"][:n], degree=degree, smoothing=smoothing)


# --------------------------------------------------------------------------------------------------
# 2. The segment list (VDI 2143 style)


def _law_entry(law: MotionLaw, index: int, count: int) -> tuple:
    """(catalogue name, b, c, d or None) of a segment's law; ValueError for a spline / polynomial."""
    if law.is_custom:
        raise ValueError(
            f"program.segments[{index}] (segment {index + 1} of {count}) has the law {law.name!r}, a spline / "
            "polynomial law that a segment list cannot name (catalogue laws only); export this program with "
            "write_table_csv or write_twincat_cnc_table instead"
        )
    name = law.name
    if name.startswith("sine_constant_cosine"):
        bcd = (float(law.b), float(law.c), float(law.d))
        if bcd in _NAMED_SCC:
            return _NAMED_SCC[bcd], None
        return "sine_constant_cosine", bcd
    if name not in CATALOGUE_LAWS:  # a law this module does not know yet: refuse rather than misname it
        raise ValueError(f"program.segments[{index}] has the law {name!r}, which the segment list cannot name")
    return name, None


def segment_list(
    program: MotionProgram,
    *,
    master_period: Optional[float] = None,
    master_unit: str = "deg",
    slave_unit: str = "mm",
    rotary: bool = False,
) -> list:
    """One dict per segment (what :func:`write_segment_list` writes): ``segment`` (1-based),
    ``master_start``, ``master_end`` (master_unit), ``slave_start``, ``slave_end`` (slave_unit),
    ``law`` (catalogue name: ``camfollower.MotionLaw.<law>()``), ``b``, ``c``, ``d`` (the
    sine_constant_cosine fractions, None for the other laws), and ``velocity_start``,
    ``velocity_end`` (d(slave)/d(master)), ``acceleration_start``, ``acceleration_end``
    (d2(slave)/d(master)2) at the segment's ends. Raises ValueError naming the segment for a spline
    or polynomial law, and for a program carrying a manufacturing error (it has no segment form)."""
    _check_program(program)
    period = _check_master(master_unit, master_period)
    factor = _check_slave_unit(slave_unit, rotary)
    if program.profile_error is not None:
        raise ValueError(
            "program carries a manufacturing (profile) error, which a segment list cannot hold: write the design "
            "program, program.with_profile_error(camfollower.ProfileError()), or the sampled lift with write_table_csv"
        )
    segs = program.segments
    scale = period / TWO_PI  # master units per rad
    rows = []
    for i, s in enumerate(segs):
        law, bcd = _law_entry(s.law, i, len(segs))
        ends = s.lift_at(np.array([s.theta_start, s.theta_end]))
        dh, d2h = np.asarray(ends["dh"], dtype=float), np.asarray(ends["d2h"], dtype=float)
        rows.append(
            {
                "segment": i + 1,
                "master_start": s.theta_start * scale,
                "master_end": s.theta_end * scale,
                "slave_start": s.h_start / factor,
                "slave_end": s.h_end / factor,
                "law": law,
                "b": None if bcd is None else bcd[0],
                "c": None if bcd is None else bcd[1],
                "d": None if bcd is None else bcd[2],
                "velocity_start": float(dh[0]) / scale / factor,
                "velocity_end": float(dh[1]) / scale / factor,
                "acceleration_start": float(d2h[0]) / scale**2 / factor,
                "acceleration_end": float(d2h[1]) / scale**2 / factor,
            }
        )
    return rows


def _segment_columns(mu: str, su: str) -> list:
    return [
        "segment",
        f"master_start_{mu}",
        f"master_end_{mu}",
        f"slave_start_{su}",
        f"slave_end_{su}",
        "law",
        "b",
        "c",
        "d",
        f"velocity_start_{su}_per_{mu}",
        f"velocity_end_{su}_per_{mu}",
        f"acceleration_start_{su}_per_{mu}2",
        f"acceleration_end_{su}_per_{mu}2",
    ]


def write_segment_list(
    path,
    program: MotionProgram,
    *,
    master_period: Optional[float] = None,
    master_unit: str = "deg",
    slave_unit: str = "mm",
    rotary: bool = False,
) -> Path:
    """Write the program as a VDI 2143-style segment list (CSV): ``# `` header lines (units, master
    period, how a row defines its segment), a line of column names, one row per segment
    (:func:`segment_list`). Only catalogue laws: a spline / polynomial segment is refused (ValueError
    naming ``program.segments[i]`` and its law). Read it back with :func:`read_segment_list`."""
    rows = segment_list(
        program, master_period=master_period, master_unit=master_unit, slave_unit=slave_unit, rotary=rotary
    )
    period = _check_master(master_unit, master_period)
    factor = _check_slave_unit(slave_unit, rotary)
    mu, su = master_unit, slave_unit
    si = "m" if not rotary else "rad"
    columns = _segment_columns(mu, su)
    lines = [
        "# camfollower cam segment list (VDI 2143 style): one row per motion segment, each a catalogue law",
        f"# format: {SEGMENT_FORMAT}",
        f"# master_unit: {mu}",
        f"# master_period: {_g(period)} ({mu} of master travel per cycle = one cam revolution, 2 pi rad of cam angle)",
        f"# slave_kind: {'rotary (oscillating follower)' if rotary else 'translating'}",
        f"# slave_unit: {su} (1 {su} = {_g(factor)} {si})",
        f"# segments: {len(rows)}",
        "# law: slave = slave_start + (slave_end - slave_start) S(x), x = (master - master_start) / (master_end - "
        "master_start), S the normalized law camfollower.MotionLaw.<law>() (S(0) = 0, S(1) = 1); "
        "sine_constant_cosine takes b, c, d (fractions of the segment, b + c + d = 1), the other laws leave them "
        "empty; VDI 2143 names: docs/ecam.md",
        f"# boundary: velocity = d(slave)/d(master) in {su}/{mu}, acceleration = d2(slave)/d(master)2 in "
        f"{su}/{mu}^2, at each segment's start and end (for reference: the law and the ends define the segment)",
        f"# columns: {','.join(columns)}",
        ",".join(columns),
    ]
    rate = TWO_PI / period  # rad per master unit, as read_segment_list converts
    for r, seg in zip(rows, program.segments):
        cells = [
            str(r["segment"]),
            _g_si(r["master_start"], rate, seg.theta_start),
            _g_si(r["master_end"], rate, seg.theta_end),
            _g_si(r["slave_start"], factor, seg.h_start),
            _g_si(r["slave_end"], factor, seg.h_end),
            r["law"],
            "" if r["b"] is None else _g(r["b"]),
            "" if r["c"] is None else _g(r["c"]),
            "" if r["d"] is None else _g(r["d"]),
            _g(r["velocity_start"]),
            _g(r["velocity_end"]),
            _g(r["acceleration_start"]),
            _g(r["acceleration_end"]),
        ]
        lines.append(",".join(cells))
    return _files.write_text(path, "\n".join(lines) + "\n")


def read_segment_list(path) -> MotionProgram:
    """The program of a segment list written by :func:`write_segment_list`: one
    ``camfollower.Segment(MotionLaw.<law>(), theta_start, theta_end, h_start, h_end)`` per row, in SI
    units (the same program; angles and lifts to within the unit conversion's last bit). The boundary
    velocity and acceleration columns are for reference and not read. Raises ValueError naming the
    file, the row and what is wrong."""
    header, body, facts, where, mu, period, su, rotary, factor = _read_units(
        path, "read_segment_list", SEGMENT_FORMAT, "segment list"
    )
    columns = _segment_columns(mu, su)
    if not body or body[0].split(",") != columns:
        got = body[0] if body else "nothing"
        raise ValueError(f"{where}: expected the column line {','.join(columns)!r}, got {got!r}")
    if not body[1:]:
        raise ValueError(f"{where}: no segment rows")
    scale = TWO_PI / period  # rad per master unit
    segments = []
    for n, line in enumerate(body[1:], start=1):
        cells = line.split(",")
        if len(cells) != len(columns):
            raise ValueError(f"{where}: row {n} has {len(cells)} cells, expected {len(columns)}")
        try:
            ms, me, ss, se = (float(c) for c in cells[1:5])
            bcd = [None if not c.strip() else float(c) for c in cells[6:9]]
        except ValueError:
            raise ValueError(f"{where}: row {n}: master / slave / b, c, d cells must be numbers: {line!r}") from None
        if not all(math.isfinite(v) for v in (ms, me, ss, se)):
            raise ValueError(f"{where}: row {n}: master and slave values must be finite")
        law_name = cells[5].strip()
        if law_name not in CATALOGUE_LAWS:
            raise ValueError(
                f"{where}: row {n}: unknown law {law_name!r}; the catalogue laws are {', '.join(CATALOGUE_LAWS)}"
            )
        if law_name == "sine_constant_cosine":
            if any(v is None for v in bcd):
                raise ValueError(f"{where}: row {n}: sine_constant_cosine needs b, c and d")
            law = MotionLaw.sine_constant_cosine(*bcd)
        else:
            if any(v is not None for v in bcd):
                raise ValueError(f"{where}: row {n}: b, c, d belong to sine_constant_cosine only, not {law_name}")
            law = getattr(MotionLaw, law_name)()
        try:
            segments.append(Segment(law, ms * scale, me * scale, ss * factor, se * factor))
        except ValueError as e:
            raise ValueError(f"{where}: row {n}: {e}") from None
    try:
        return MotionProgram(segments)
    except ValueError as e:
        raise ValueError(f"{where}: {e}") from None


# --------------------------------------------------------------------------------------------------
# 3. The TwinCAT CNC / ISG MC platform cam table (ASCII interpreter)


def _check_twincat_name(name) -> str:
    if (
        not isinstance(name, str)
        or not 1 <= len(name) <= 30
        or not all(33 <= ord(ch) <= 126 for ch in name)
        or name[0] in "#;"
    ):
        raise ValueError(
            "name must be 1 to 30 printable ASCII characters without blanks (the Tablename), not starting with "
            f"'#' or ';', got {name!r}"
        )
    return name


def write_twincat_cnc_table(
    path,
    program: MotionProgram,
    *,
    points: int = 360,
    name: str = "camfollower",
    table_id: int = 1,
    function_type: int = 1,
    rotary: bool = False,
    decimals: int = 4,
    decimal_separator: str = ",",
) -> Path:
    """Write the program as a cam table for the ASCII interpreter of the TwinCAT CNC / ISG MC platform
    (PLCopen cam functions, MC_CamIn), as Beckhoff documents it (TWINCAT_CNC_SOURCE):

    - comment lines (``#`` first) with the units and the program; then the header ``Tablename``
      (``name``: no blanks), ``Tabletype = 3`` (TABLE_ONE_COLUMN_REAL64), ``Table-ID``
      (``table_id``, an integer >= 1), ``Functiontype`` (``function_type``: 0 STEP_DIRECT, 1 LINEAR,
      2 POLYNOM_3; MC_CamIn's TableFctType selects the interpolation actually used) and ``Lines``
      (``points``);
    - ``Begintable``, one slave position per line, ``EndTable``.

    The lines are equidistant interpolation points over the master's modulo range 0 .. 360 deg: line k
    (k = 0 .. points - 1) is the slave at master k 360 / points deg; the table is closed by definition
    (360 deg is 0 deg), so the repeated end point is not written. The slave is in the MC platform's
    unit: 1E-4 mm (``rotary=False``) or 1E-4 deg (``rotary=True``, the program's lift in rad).
    ``decimals`` digits after the decimal separator (4 as in Beckhoff's example table data, at most 9;
    0 writes whole numbers of 1E-4 mm, the controller's resolution, and no separator at all),
    ``decimal_separator`` "," as in Beckhoff's examples, or ".". Returns the path."""
    _check_program(program)
    points = _check_points(points)
    _check_twincat_name(name)
    if isinstance(table_id, bool) or not isinstance(table_id, numbers.Integral) or not 1 <= table_id <= 2**31 - 1:
        raise ValueError(f"table_id must be an integer in [1, {2**31 - 1}] (the Table-ID), got {table_id!r}")
    if isinstance(function_type, bool) or function_type not in (0, 1, 2):
        raise ValueError(
            "function_type must be 0 (STEP_DIRECT), 1 (LINEAR) or 2 (POLYNOM_3) for an interpolation point table, "
            f"got {function_type!r}"
        )
    if not isinstance(rotary, bool):
        raise ValueError(f"rotary must be True (oscillating follower, lift in rad) or False, got {rotary!r}")
    if isinstance(decimals, bool) or not isinstance(decimals, numbers.Integral) or not 0 <= decimals <= 9:
        raise ValueError(f"decimals must be an integer in [0, 9], got {decimals!r}")
    if decimal_separator not in (",", "."):
        raise ValueError(f"decimal_separator must be ',' or '.', got {decimal_separator!r}")

    theta = TWO_PI * np.arange(points) / points
    h = np.asarray(program.evaluate(theta)["h"], dtype=float)
    per_si = _TWINCAT_PER_RAD if rotary else _TWINCAT_PER_M  # file units per m (per rad)
    values = np.round(h * per_si, int(decimals)) + 0.0  # + 0.0: no "-0"
    if decimals == 0:
        cells = [str(int(v)) for v in values.tolist()]
    else:
        cells = [f"{v:.{int(decimals)}f}".replace(".", decimal_separator) for v in values.tolist()]
    unit = "1E-4 deg" if rotary else "1E-4 mm (0.1 um)"
    si_unit = "rad" if rotary else "m"
    lines = [
        "# camfollower cam table for the TwinCAT CNC / ISG MC platform ASCII interpreter (MC_CamIn)",
        f"# format: {TWINCAT_CNC_SOURCE}",
        f"# interpolation point table: {TWINCAT_CNC_POINT_TABLES}",
        f"# lines: {points} equidistant slave positions; line k (k = 0 .. {points - 1}) is at master k * 360 / {points} "
        "deg of the master's modulo range 0 .. 360 deg (one cam revolution); closed: 360 deg is 0 deg",
        f"# slave unit: {unit}; the program's lift in {si_unit} = value / {_g(per_si)}",
        f"# program: {_program_summary(program, 'mm' if not rotary else 'rad', 1e-3 if not rotary else 1.0)}",
        f"Tablename = {name}",
        "Tabletype = 3 # 3 = TABLE_ONE_COLUMN_REAL64",
        f"Table-ID = {int(table_id)} # Table-ID",
        f"Functiontype = {int(function_type)} # {int(function_type)} = {_TWINCAT_FUNCTION_TYPES[int(function_type)]}",
        f"Lines = {points}",
        "Begintable",
        *cells,
        "EndTable",
    ]
    return _files.write_text(path, "\n".join(lines) + "\n")


def _twincat_number(token: str) -> float:
    return float(token.replace(",", "."))


def read_twincat_cnc_table(path, *, rotary: bool = False) -> dict:
    """Read an interpolation point table of the TwinCAT CNC / ISG MC platform ASCII interpreter (one
    column: Tabletype 1, 2 or 3), by the documented rules: ``#`` or ``;`` first on a line makes it a
    comment, tokens are separated by blanks or tabs (and ``=`` in the header), a line's tokens after
    the expected ones are ignored, a decimal comma or point. Returns ``name``, ``table_type``,
    ``table_id``, ``function_type`` (None when absent), ``lines``, ``values`` (the slave column as
    written, 1E-4 mm or 1E-4 deg), ``master_deg`` (k 360 / lines), and in SI units ``theta`` (rad)
    and ``h`` (m; rad with ``rotary=True``: the file does not say which). Raises ValueError naming
    the file and line."""
    if not isinstance(rotary, bool):
        raise ValueError(f"rotary must be True (the values are 1E-4 deg) or False (1E-4 mm), got {rotary!r}")
    fname, text = _read_text(path)
    where = f"read_twincat_cnc_table: {fname!r}"
    header: dict = {}
    values: list = []
    state = "header"
    keys = {"tablename": "name", "tabletype": "table_type", "table-id": "table_id", "functiontype": "function_type"}
    keys.update({"function type": "function_type", "lines": "lines"})
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line[0] in "#;":
            continue
        tokens = line.split()
        word = tokens[0].lower()
        if state == "header":
            if word in ("begintable", "begin-table"):
                state = "data"
                continue
            m = re.match(r"\s*([A-Za-z][A-Za-z -]*?)\s*=\s*(\S+)", line)
            if not m or m.group(1).lower() not in keys:
                raise ValueError(f"{where}: line {number}: not a header entry (Tablename, Tabletype, ...): {raw!r}")
            key = keys[m.group(1).lower()]
            if key == "name":
                header[key] = m.group(2)
            else:
                try:
                    header[key] = int(m.group(2))
                except ValueError:
                    raise ValueError(f"{where}: line {number}: {m.group(1)} must be an integer: {raw!r}") from None
        elif state == "data":
            if word == "endtable":
                state = "end"
                continue
            try:
                values.append(_twincat_number(tokens[0]))
            except ValueError:
                raise ValueError(f"{where}: line {number}: not a number: {raw!r}") from None
            if not math.isfinite(values[-1]):
                raise ValueError(f"{where}: line {number}: not a finite number: {raw!r}")
    if state != "end":
        missing = "Begintable" if state == "header" else "EndTable"
        raise ValueError(f"{where}: no {missing} line")
    for key, word in (("name", "Tablename"), ("table_type", "Tabletype"), ("lines", "Lines")):
        if key not in header:
            raise ValueError(f"{where}: the header has no {word} entry")
    if header["table_type"] not in (1, 2, 3):
        kind = _TWINCAT_TABLE_TYPES.get(header["table_type"], "unknown")
        raise ValueError(
            f"{where}: Tabletype {header['table_type']} ({kind}) is not read here: only the one-column interpolation "
            "point tables (Tabletype 1, 2 or 3)"
        )
    if header["lines"] != len(values):
        raise ValueError(f"{where}: Lines = {header['lines']} but the table holds {len(values)} values")
    if len(values) < 1:
        raise ValueError(f"{where}: the table holds no values")
    n = len(values)
    per_si = _TWINCAT_PER_RAD if rotary else _TWINCAT_PER_M
    arr = np.array(values, dtype=float)
    return {
        "name": header["name"],
        "table_type": header["table_type"],
        "table_id": header.get("table_id"),
        "function_type": header.get("function_type"),
        "lines": n,
        "values": arr,
        "master_deg": 360.0 * np.arange(n) / n,
        "theta": TWO_PI * np.arange(n) / n,
        "h": arr / per_si,
        "rotary": rotary,
    }


def program_from_twincat_cnc_table(
    path, *, rotary: bool = False, degree: int = 5, smoothing: float = 0.0
) -> MotionProgram:
    """The program through a TwinCAT CNC / ISG MC platform interpolation point table
    (:func:`read_twincat_cnc_table`): ``MotionProgram.from_table(theta, h, degree, smoothing)``, the
    table being periodic by definition."""
    table = read_twincat_cnc_table(path, rotary=rotary)
    if table["lines"] < MIN_POINTS:
        raise ValueError(
            f"program_from_twincat_cnc_table: {MIN_POINTS} lines at least, the table holds {table['lines']}"
        )
    return MotionProgram.from_table(table["theta"], table["h"], degree=degree, smoothing=smoothing)
