# SPDX-License-Identifier: BSD-3-Clause
"""Cam outlines for manufacturing: the cam surface and a cutter's centre path as arrays, CSV or DXF.

The geometry comes from the compiled core (``include/camfollower/geometry/export.hpp``), for any of
the four follower types:

- ``theta``: cam angles 2 pi k / points (rad), k = 0..points-1; the outline is closed (the last point
  joins the first).
- ``surface``: the cam surface in the cam frame, origin at the cam centre, in ``unit``.
- ``cutter``: the centre of a cutter (milling cutter or grinding wheel) of radius ``cutter_radius``
  (m): the surface offset outward along its normal by that radius. For a roller follower with a
  cutter as large as the roller it is the pitch curve. A cutter larger than the tightest concave
  radius of the surface would gouge it and is refused (ValueError naming the cam angle).

Conventions stated in every file: the cam turns counter-clockwise viewed from +z as theta grows
(docs/followers.md), so the rows run clockwise round the cam; at theta = 0 the cam frame coincides
with the ground frame and the zero mark is the contact point at theta = 0 (the first row).

A barrel (cylindrical) cam has no disk outline: its groove comes from :func:`groove_points`,
:func:`write_groove_csv` and :func:`write_groove_dxf` (the exact walls along the depth for a
cylindrical or the ideal tapered roller, the pressure angle at each radius and a 4-axis machining
path; ``include/camfollower/geometry/barrel_groove.hpp``).

Files are written atomically by the core's writer: a temporary in the target's folder, then a
rename; a target that exists and is not a regular file (a directory, FIFO or device) is refused and
a failure leaves nothing behind. The DXF writer needs ezdxf (``pip install camfollower[dxf]``).
"""

from __future__ import annotations

import io
import math
import numbers
import os
from typing import Optional

import numpy as np

from . import _core, _files

# $INSUNITS codes of the DXF format for the library's length units (the factors live in the core).
_DXF_INSUNITS = {"m": 6, "mm": 4, "um": 13, "inch": 1}

SURFACE_LAYER = "CAM_SURFACE"
CUTTER_LAYER = "CUTTER_PATH"
REFERENCE_LAYER = "REFERENCE"


def _check(points, cutter_radius, unit):
    if isinstance(points, bool) or not isinstance(points, numbers.Integral) or not 3 <= points <= _core.MAX_POINTS:
        raise ValueError(f"points must be an integer in [3, {_core.MAX_POINTS}], got {points!r}")
    if cutter_radius is not None:
        if (
            isinstance(cutter_radius, bool)
            or not isinstance(cutter_radius, numbers.Real)
            or not (math.isfinite(cutter_radius) and cutter_radius >= 0)
        ):
            raise ValueError(f"cutter_radius must be None or a finite number >= 0 (m), got {cutter_radius!r}")
    units = _core.length_units()
    if unit not in units:
        raise ValueError(f"unit must be one of {', '.join(units)}, got {unit!r}")
    return int(points), None if cutter_radius is None else float(cutter_radius)


def profile_points(
    follower, program, *, points: int = 3600, cutter_radius: Optional[float] = None, unit: str = "mm"
) -> dict:
    """The cam outline as numpy arrays: ``theta`` (rad), ``surface_x``, ``surface_y`` (cam frame, in
    ``unit``), ``normal_x``, ``normal_y`` (outward unit normal), and with a ``cutter_radius`` (m)
    ``cutter_x``, ``cutter_y``; also ``unit``, ``cutter_radius`` and ``notes`` (the header lines that
    the CSV and DXF files carry: units, rotation, zero reference, follower, cutter, points)."""
    points, cutter_radius = _check(points, cutter_radius, unit)
    return _core.cam_outline(follower, program, points, cutter_radius, unit)


def mounting_note(frame_angle: float) -> list:
    """The header line that says where a cam whose contact frame is turned by ``frame_angle`` (rad; a
    conjugate pair's return cam) is mounted on the shaft, or none for an angle of 0."""
    if frame_angle == 0.0:
        return []
    return [
        f"mounting: this cam's frame is its contact's, turned by {math.degrees(frame_angle):.10g} deg from the ground "
        "frame about the shaft axis (counter-clockwise seen from +z): mount it with its zero mark that far ahead "
        "of the zero mark of a cam drawn in the ground frame (a conjugate pair's lift cam)"
    ]


def write_csv(
    path,
    follower,
    program,
    *,
    points: int = 3600,
    cutter_radius: Optional[float] = None,
    unit: str = "mm",
    frame_angle: float = 0.0,
) -> None:
    """Write the outline as CSV: commented header (``# ``) with the conventions, then the columns
    ``theta_rad,surface_x_<unit>,surface_y_<unit>[,cutter_x_<unit>,cutter_y_<unit>]``, one row per
    point (17 significant digits). Read it back with
    ``numpy.loadtxt(path, delimiter=",", skiprows=<header lines + 1>)`` or any CSV reader with ``#``
    comments. ``frame_angle`` (rad): the contact's frame angle, stated as the cam's mounting (a
    conjugate pair's return cam)."""
    points, cutter_radius = _check(points, cutter_radius, unit)
    notes = mounting_note(float(frame_angle))
    _core.write_cam_csv(os.fspath(path), follower, program, points, cutter_radius, unit, notes)


def _ezdxf():
    try:
        import ezdxf
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "camfollower.export.write_dxf needs ezdxf: pip install camfollower[dxf] (or pip install ezdxf)"
        ) from e
    return ezdxf


def _new_drawing(unit: str, notes, layers):
    """An R2010 drawing in ``unit`` ($INSUNITS, $MEASUREMENT) with the ``notes`` as custom header
    properties camfollower_1, ... and the ``layers`` ((name, colour), ...): (document, model space)."""
    doc = _ezdxf().new("R2010")
    doc.header["$INSUNITS"] = _DXF_INSUNITS[unit]
    doc.header["$MEASUREMENT"] = 0 if unit == "inch" else 1
    for k, note in enumerate(notes, start=1):
        doc.header.custom_vars.append(f"camfollower_{k}", note)
    for name, color in layers:
        doc.layers.add(name, color=color)
    return doc, doc.modelspace()


def _save_drawing(doc, target: str) -> None:
    stream = io.StringIO()
    doc.write(stream)
    _files.write_bytes(target, doc.encode(stream.getvalue()))


def write_dxf(
    path,
    follower,
    program,
    *,
    points: int = 3600,
    cutter_radius: Optional[float] = None,
    unit: str = "mm",
    frame_angle: float = 0.0,
) -> None:
    """Write the outline as a DXF drawing (R2010) in ``unit`` ($INSUNITS set accordingly):

    - layer ``CAM_SURFACE``: the cam surface, one closed LWPOLYLINE of ``points`` vertices;
    - layer ``CUTTER_PATH``: the cutter-centre path, the same (only with a ``cutter_radius``, m);
    - layer ``REFERENCE``: a cross at the cam centre, the zero mark (a line from the centre through
      the contact point at theta = 0, labelled ``THETA = 0``) and the rotation (an arc with an
      arrowhead turning counter-clockwise, labelled ``CCW``).

    The header lines of the CSV are stored as DXF custom header properties (``camfollower_1``, ...),
    with the mounting note for a ``frame_angle`` (rad) other than 0. Written atomically, like the CSV."""
    points, cutter_radius = _check(points, cutter_radius, unit)
    target = os.fspath(path)
    _files.check_target(target)  # before the drawing is built
    outline = _core.cam_outline(follower, program, points, cutter_radius, unit)
    doc, msp = _new_drawing(
        unit,
        list(outline["notes"]) + mounting_note(float(frame_angle)),
        ((SURFACE_LAYER, 7), (CUTTER_LAYER, 1), (REFERENCE_LAYER, 3)),
    )

    sx, sy = outline["surface_x"], outline["surface_y"]
    msp.add_lwpolyline(np.column_stack([sx, sy]).tolist(), format="xy", close=True, dxfattribs={"layer": SURFACE_LAYER})
    if cutter_radius is not None:
        msp.add_lwpolyline(
            np.column_stack([outline["cutter_x"], outline["cutter_y"]]).tolist(),
            format="xy",
            close=True,
            dxfattribs={"layer": CUTTER_LAYER},
        )

    radii = np.hypot(sx, sy)
    inner, outer = float(radii.min()), float(radii.max())
    text = 0.04 * outer
    ref = {"layer": REFERENCE_LAYER}
    # Centre cross.
    msp.add_line((-0.1 * inner, 0.0), (0.1 * inner, 0.0), dxfattribs=ref)
    msp.add_line((0.0, -0.1 * inner), (0.0, 0.1 * inner), dxfattribs=ref)
    # Zero mark: from the centre through the contact point at theta = 0, past the outline.
    zero = math.atan2(sy[0], sx[0])
    u = (math.cos(zero), math.sin(zero))
    reach = outer + 4 * text
    msp.add_line((0.0, 0.0), (reach * u[0], reach * u[1]), dxfattribs=ref)
    msp.add_text("THETA = 0", height=text, rotation=math.degrees(zero), dxfattribs=ref).set_placement(
        ((reach + text) * u[0], (reach + text) * u[1])
    )
    # Rotation: a counter-clockwise arc with an arrowhead at its end, inside the cam.
    r = 0.5 * inner
    a0, a1 = zero + math.radians(30), zero + math.radians(120)
    msp.add_arc((0.0, 0.0), r, math.degrees(a0), math.degrees(a1), dxfattribs=ref)
    tip = (r * math.cos(a1), r * math.sin(a1))
    t = (-math.sin(a1), math.cos(a1))  # counter-clockwise tangent
    n = (math.cos(a1), math.sin(a1))
    size = 0.15 * r
    msp.add_lwpolyline(
        [
            (tip[0] + size * t[0], tip[1] + size * t[1]),
            (tip[0] + 0.5 * size * n[0], tip[1] + 0.5 * size * n[1]),
            (tip[0] - 0.5 * size * n[0], tip[1] - 0.5 * size * n[1]),
        ],
        format="xy",
        close=True,
        dxfattribs=ref,
    )
    mid = 0.5 * (a0 + a1)
    msp.add_text("CCW", height=text, dxfattribs=ref).set_placement((0.6 * r * math.cos(mid), 0.6 * r * math.sin(mid)))
    _save_drawing(doc, target)


GROOVE_TOP_LAYER = "GROOVE_TOP"
GROOVE_BOTTOM_LAYER = "GROOVE_BOTTOM"
PITCH_LAYER = "PITCH_CURVE"
ROLLERS = ("cylindrical", "tapered")


def _check_groove(points, clearance, roller, unit):
    points, _ = _check(points, None, unit)
    if isinstance(clearance, bool) or not isinstance(clearance, numbers.Real) or not math.isfinite(clearance):
        raise ValueError(f"clearance must be a finite number >= 0 (m), got {clearance!r}")
    if roller not in ROLLERS:
        raise ValueError(f"roller must be one of {', '.join(ROLLERS)}, got {roller!r}")
    return points, float(clearance)


def groove_points(
    follower, program, *, points: int = 3600, clearance: float = 0.0, roller: str = "cylindrical"
) -> dict:
    """A barrel cam's groove (``BarrelRoller`` or ``BarrelArmRoller``) as numpy arrays, SI units:
    ``theta`` (rad), ``radii`` (top, pitch, bottom; m), ``centre_angle``/``centre_z`` (the roller
    centre at the pitch radius: position round the cam in rad, the roller's station being at
    ``theta``, and height along the cam axis in m), ``lift_angle``/``lift_z`` and
    ``back_angle``/``back_z`` (3 x points: the flank that lifts the roller and the opposite one, a
    ``clearance`` (m) away), ``pressure_angle`` (3 x points, rad, lifting flank), and the 4-axis
    machining path ``cutter_cross``, ``cutter_axial``, ``cutter_plunge`` (m) of a cutter shaped as
    the roller (``roller``: "cylindrical" or the ideal "tapered"), larger by clearance / 2."""
    points, clearance = _check_groove(points, clearance, roller, "m")
    return _core.barrel_groove(follower, program, points, clearance, roller)


def write_groove_csv(
    path, follower, program, *, points: int = 3600, clearance: float = 0.0, roller: str = "cylindrical", unit="mm"
) -> None:
    """Write the groove as CSV: commented header (units, frame, radii, roller, machining axes), then per
    cam angle ``theta_deg``, the roller centre, both flanks and the pressure angle at the top, pitch and
    bottom radii (angles in deg, lengths in ``unit``) and the machining path."""
    points, clearance = _check_groove(points, clearance, roller, unit)
    _core.write_barrel_groove_csv(os.fspath(path), follower, program, points, clearance, roller, unit)


def write_groove_dxf(
    path, follower, program, *, points: int = 3600, clearance: float = 0.0, roller: str = "cylindrical", unit="mm"
) -> None:
    """Write the developed groove as a DXF drawing (R2010) in ``unit``: x = the position round the cam
    as arc length on the cylinder's outer radius, y = the height along the cam axis. Layers
    ``GROOVE_TOP`` (both flanks at the top radius, two open polylines over one turn), ``GROOVE_BOTTOM``
    (the same at the groove's bottom, its angles drawn on the outer radius too) and ``PITCH_CURVE``
    (the roller centre). Written atomically."""
    points, clearance = _check_groove(points, clearance, roller, unit)
    target = os.fspath(path)
    _files.check_target(target)
    g = _core.barrel_groove(follower, program, points, clearance, roller)
    scale = 1.0 / _core.length_units()[unit]
    outer = float(g["radii"][0])

    def polyline(angle, z, layer):
        xy = np.column_stack([scale * outer * np.asarray(angle), scale * np.asarray(z)])
        xy = np.vstack([xy, xy[:1] + [scale * outer * 2 * math.pi, 0.0]])  # one turn: back to the start + 2 pi R
        msp.add_lwpolyline(xy.tolist(), format="xy", dxfattribs={"layer": layer})

    notes = [
        "camfollower barrel cam groove, developed on the outer radius",
        f"x = position round the cam as arc length at radius {scale * outer:g} {unit}; y = height along the cam axis",
        f"roller: {roller}; groove clearance {scale * clearance:g} {unit}",
    ]
    doc, msp = _new_drawing(unit, notes, ((GROOVE_TOP_LAYER, 7), (GROOVE_BOTTOM_LAYER, 5), (PITCH_LAYER, 3)))
    for i, layer in ((0, GROOVE_TOP_LAYER), (2, GROOVE_BOTTOM_LAYER)):
        polyline(g["lift_angle"][i], g["lift_z"][i], layer)
        polyline(g["back_angle"][i], g["back_z"][i], layer)
    polyline(g["centre_angle"], g["centre_z"], PITCH_LAYER)
    _save_drawing(doc, target)


def is_barrel(follower) -> bool:
    """Does ``follower`` run in a barrel cam's groove (its cam has no disk outline)?"""
    return isinstance(follower, (_core.BarrelRoller, _core.BarrelArmRoller))


__all__ = [
    "profile_points",
    "write_csv",
    "write_dxf",
    "groove_points",
    "write_groove_csv",
    "write_groove_dxf",
    "is_barrel",
    "mounting_note",
    "SURFACE_LAYER",
    "CUTTER_LAYER",
    "REFERENCE_LAYER",
    "GROOVE_TOP_LAYER",
    "GROOVE_BOTTOM_LAYER",
    "PITCH_LAYER",
]
