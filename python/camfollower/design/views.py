# SPDX-License-Identifier: BSD-3-Clause
"""What the design page shows, computed by the library and returned as plain numbers (no plotting):
kinematics (SVAJ, profile, pressure angle, radius of curvature and their limits), the flexible
response at the camshaft's speed (its periodic steady state), and one speed of the margin curve.

Angles are the contact's own cam angle in degrees; lifts in mm (an arm's in deg); everything else in
SI at the camshaft's speed. The page plots exactly these arrays, so a test can compare them with the
library's numbers for the same design.
"""

from __future__ import annotations

import math
import time
from typing import Any, Dict, Optional

import numpy as np

from .. import response as _response
from ..config import Config
from ..export import is_barrel

#: Cam angles of the kinematic curves: 0.5 deg apart, 0 and 360 both included.
ANGLES = 721
#: Points per response curve the page draws (min/max pairs of the orbit's steps beyond it).
RESPONSE_POINTS = 1024
#: Steps per revolution of the first, quick response (its accuracy from an orbit at half the step).
QUICK_STEPS = 2048
#: Accuracy the page refines the response to, and runs the margin curve at (the studies' default).
REFINED_ACCURACY = 1e-3


def contact_of(case: Config, name: Optional[str]) -> Dict[str, Any]:
    contacts = case.builder.contacts
    if not contacts:
        raise ValueError("the mechanism has no cam contact: nothing to design (add a [[contact]])")
    for c in contacts:
        if name is None or c["name"] == name:
            return c
    raise ValueError(
        f"contact: no contact named {name!r}; the mechanism's contacts are {[c['name'] for c in contacts]}"
    )


def lift_scale(follower) -> tuple:
    """(factor, unit) from the lift in SI to how the page shows it: mm, or deg for an arm."""
    return (1e3, "mm") if getattr(follower, "translating", True) else (180.0 / math.pi, "deg")


def kinematics(case: Config, contact: Optional[str] = None) -> Dict[str, Any]:
    """SVAJ at the camshaft's speed, the cam profile in its own frame, pressure angle and radius of
    curvature, their extremes, and the library's check of the profile (``check``: None, or its
    message: undercut, cusp, pressure angle reaching 90 deg)."""
    c = contact_of(case, contact)
    follower, program = c["follower"], c["program"]
    omega = case.mechanism.omega
    theta = np.linspace(0.0, 2.0 * math.pi, ANGLES)
    d = program.evaluate(theta)
    scale, unit = lift_scale(follower)
    rate = "m" if unit == "mm" else "rad"
    out: Dict[str, Any] = {
        "contact": c["name"],
        "rpm": float(case.mechanism.camshaft_speed_rpm),
        "theta_deg": np.degrees(theta),
        "lift": scale * np.asarray(d["h"]),
        "lift_unit": unit,
        "velocity": omega * np.asarray(d["dh"]),
        "acceleration": omega**2 * np.asarray(d["d2h"]),
        "jerk": omega**3 * np.asarray(d["d3h"]),
        "rate_unit": rate,
        "check": None,
        "profile": None,
    }
    try:
        follower.check(program)
    except ValueError as e:
        out["check"] = str(e)
    if is_barrel(follower):
        return out  # a barrel cam has no plate profile to draw
    p = follower.profile(program, theta)
    out["profile"] = {
        "surface_x": 1e3 * np.asarray(p["surface_x"]),
        "surface_y": 1e3 * np.asarray(p["surface_y"]),
        "reference_x": 1e3 * np.asarray(p["reference_x"]),
        "reference_y": 1e3 * np.asarray(p["reference_y"]),
        "roller_radius": 1e3 * float(getattr(follower, "roller_radius", 0.0) or 0.0),
    }
    out["pressure_angle_deg"] = np.degrees(np.asarray(p["pressure_angle"]))
    out["surface_radius_mm"] = 1e3 * np.asarray(p["surface_radius"])
    out["base_radius_mm"] = 1e3 * float(getattr(follower, "base_radius", 0.0) or 0.0)
    if out["check"] is None:  # the extremes are defined on a followable profile
        at, alpha = follower.max_pressure_angle(program)
        rho_at, rho = follower.min_surface_radius(program)
        out["max_pressure_angle"] = {"deg": abs(math.degrees(alpha)), "at_deg": math.degrees(at)}
        out["min_surface_radius"] = {"mm": 1e3 * rho, "at_deg": math.degrees(rho_at)}
    return out


def _envelope(x: np.ndarray, ys: list, points: int) -> tuple:
    """At most `points` samples per curve: each bucket of steps as its smallest and largest value in
    their order, so a ringing faster than the drawn grid keeps its extremes (a stride would alias)."""
    n = x.size
    if n <= points:
        return x, ys
    buckets = points // 2
    edges = np.linspace(0, n, buckets + 1).astype(int)
    idx = []
    ref = ys[0]
    for lo, hi in zip(edges[:-1], edges[1:]):
        seg = ref[lo:hi]
        a, b = lo + int(np.nanargmin(seg)), lo + int(np.nanargmax(seg))
        idx.extend(sorted({a, b}))
    idx = np.asarray(idx)
    return x[idx], [y[idx] for y in ys]


def response(
    case: Config,
    contact: Optional[str] = None,
    *,
    steps_per_revolution: Optional[int] = None,
    accuracy: Optional[float] = None,
    guess=None,
    stop_at_loss: bool = False,
) -> Dict[str, Any]:
    """The periodic steady state at the camshaft's speed (camfollower.response.steady_response: at
    ``steps_per_revolution`` with its accuracy estimated, or refined to ``accuracy``), as curves over
    one revolution against the contact's cam angle: the follower DOF's acceleration and the rigid
    follower's ω²h″, the contact force and where contact is lost (a groove: ``outer_force``, the other
    flank's, and lost where the roller touches neither), and the residual vibration (the DOF
    less its quasi-static path) in the dwells. ``summary`` is the study's row without its arrays;
    ``orbit`` the orbit (a warm start for the next design); ``seconds`` what it took.
    ``stop_at_loss``: a response that loses contact and does not settle is not chased further (as
    steady_response's: at most 12 shooting iterations and 60 transient revolutions)."""
    t0 = time.perf_counter()
    c = contact_of(case, contact)
    m = case.mechanism
    if accuracy is None and steps_per_revolution is None:
        steps_per_revolution = QUICK_STEPS
    row = _response.steady_response(
        m,
        contact=c["name"],
        accuracy=accuracy,
        steps_per_revolution=steps_per_revolution,
        guess=guess,
        multipliers=False,
        keep_orbit=True,
        fallback="transient",
        stop_at_loss=stop_at_loss,
    )
    orbit = row.pop("orbit")
    rec = orbit.record(m)
    dof, name = c["follower_dof"], c["name"]
    shaft = np.asarray(rec["theta"])[1:]
    cam = np.mod(shaft + float(c["phase"]), 2.0 * math.pi)
    order = np.argsort(cam, kind="stable")
    cam = cam[order]
    a = np.asarray(rec[f"a.{dof}"])[1:][order]
    force = np.asarray(rec[f"{name}.force"])[1:][order]
    touching = np.asarray(rec[f"{name}.in_contact"])[1:][order] > 0.5
    grooved = c.get("groove") is not None
    outer = None
    if grooved:  # form-closed: the roller leaves the cam only when it touches neither flank
        outer = np.asarray(rec[f"{name}.outer_force"])[1:][order]
        touching |= np.asarray(rec[f"{name}.outer_in_contact"])[1:][order] > 0.5
    q = np.asarray(rec[f"q.{dof}"])[1:][order]
    program = c["program"]
    in_dwell = np.zeros(cam.size, dtype=bool)
    for seg in _response._dwells(program):
        in_dwell |= (cam >= seg.theta_start) & (cam < seg.theta_end)
    residual = np.full(cam.size, np.nan)
    if in_dwell.any():
        qs = _response._quasi_static(m, dof, np.mod(shaft[order], 2.0 * math.pi))
        residual[in_dwell] = (q - qs)[in_dwell]
    curves = [a, force, (~touching).astype(float), residual] + ([outer] if grooved else [])
    x, drawn = _envelope(np.degrees(cam), curves, RESPONSE_POINTS)
    a_e, f_e, lost_e, r_e = drawn[:4]
    rigid = m.omega**2 * np.asarray(program.evaluate(np.radians(x))["d2h"])
    summary = {k: v for k, v in row.items() if k not in ("dwells", "harmonics")}
    return {
        "theta_deg": x,
        "acceleration": a_e,
        "rigid_acceleration": rigid,
        "force": f_e,
        "outer_force": drawn[4] if grooved else None,
        "lost": lost_e > 0.5,
        "residual": r_e,
        "dof": dof,
        "unit": "rad" if not getattr(c["follower"], "translating", True) else "m",
        "summary": summary,
        "dwells": row.get("dwells", []),
        "orbit": orbit,
        "seconds": time.perf_counter() - t0,
    }


def margin_point(case: Config, rpm: float, contact: Optional[str] = None, guess=None) -> Dict[str, Any]:
    """One speed of the margin curve: the steady state's row at ``rpm`` (REFINED_ACCURACY)."""
    m = case.mechanism.with_camshaft_speed_rpm(float(rpm))
    row = _response.steady_response(
        m,
        contact=contact_of(case, contact)["name"],
        accuracy=REFINED_ACCURACY,
        guess=guess,
        multipliers=False,
        fallback="transient",
        keep_orbit=True,
    )
    return row


__all__ = ["ANGLES", "QUICK_STEPS", "REFINED_ACCURACY", "kinematics", "margin_point", "response"]
