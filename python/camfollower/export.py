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


def write_csv(
    path, follower, program, *, points: int = 3600, cutter_radius: Optional[float] = None, unit: str = "mm"
) -> None:
    """Write the outline as CSV: commented header (``# ``) with the conventions, then the columns
    ``theta_rad,surface_x_<unit>,surface_y_<unit>[,cutter_x_<unit>,cutter_y_<unit>]``, one row per
    point (17 significant digits). Read it back with
    ``numpy.loadtxt(path, delimiter=",", skiprows=<header lines + 1>)`` or any CSV reader with ``#``
    comments."""
    points, cutter_radius = _check(points, cutter_radius, unit)
    _core.write_cam_csv(os.fspath(path), follower, program, points, cutter_radius, unit)


def _ezdxf():
    try:
        import ezdxf
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "camfollower.export.write_dxf needs ezdxf: pip install camfollower[dxf] (or pip install ezdxf)"
        ) from e
    return ezdxf


def write_dxf(
    path, follower, program, *, points: int = 3600, cutter_radius: Optional[float] = None, unit: str = "mm"
) -> None:
    """Write the outline as a DXF drawing (R2010) in ``unit`` ($INSUNITS set accordingly):

    - layer ``CAM_SURFACE``: the cam surface, one closed LWPOLYLINE of ``points`` vertices;
    - layer ``CUTTER_PATH``: the cutter-centre path, the same (only with a ``cutter_radius``, m);
    - layer ``REFERENCE``: a cross at the cam centre, the zero mark (a line from the centre through
      the contact point at theta = 0, labelled ``THETA = 0``) and the rotation (an arc with an
      arrowhead turning counter-clockwise, labelled ``CCW``).

    The header lines of the CSV are stored as DXF custom header properties (``camfollower_1``, ...).
    Written atomically, like the CSV."""
    points, cutter_radius = _check(points, cutter_radius, unit)
    target = os.fspath(path)
    _files.check_target(target)  # before the drawing is built
    outline = _core.cam_outline(follower, program, points, cutter_radius, unit)
    ezdxf = _ezdxf()

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = _DXF_INSUNITS[unit]
    doc.header["$MEASUREMENT"] = 0 if unit == "inch" else 1
    for k, note in enumerate(outline["notes"], start=1):
        doc.header.custom_vars.append(f"camfollower_{k}", note)
    doc.layers.add(SURFACE_LAYER, color=7)
    doc.layers.add(CUTTER_LAYER, color=1)
    doc.layers.add(REFERENCE_LAYER, color=3)
    msp = doc.modelspace()

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

    stream = io.StringIO()
    doc.write(stream)
    _files.write_bytes(target, doc.encode(stream.getvalue()))


__all__ = ["profile_points", "write_csv", "write_dxf", "SURFACE_LAYER", "CUTTER_LAYER", "REFERENCE_LAYER"]
