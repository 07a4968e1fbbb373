# SPDX-License-Identifier: BSD-3-Clause
"""Plots for any cam and any result (matplotlib, an optional extra: ``pip install camfollower[plot]``).

Every function draws into new axes (or the ``ax``/``axes`` given) and returns the Figure, so it can
be saved, shown or changed. Angles are shown in degrees, lengths in mm; the data stay SI.

- :func:`svaj`: lift, velocity, acceleration and jerk of a motion program (a length, or with
  ``angular=True`` an oscillating follower's arm rotation);
- :func:`profile`: the cam surface, the follower's reference curve (a roller's pitch curve) and the
  contact point at one cam angle; an undercut cam is drawn and flagged in the title, not refused;
- :func:`pressure_angle_and_curvature`: both along the revolution (radii beyond the display
  limit left as a gap, the limit marked);
- :func:`acceleration`: a follower DOF's simulated acceleration against the rigid ω²h″, over one
  revolution of the cam's own angle whatever revolutions were recorded;
- :func:`contact_force`: a contact's force with its intervals without contact shaded;
- :func:`spectrum`: an amplitude spectrum, labelled with its quantity and unit, natural frequencies
  marked.

Angle axes run 0-360° per revolution: a recorded run is folded onto one revolution
(:func:`per_revolution`), its line broken where the angle wraps.
"""

from __future__ import annotations

import math
from typing import Optional, Sequence

import numpy as np

from . import _core
from . import analysis as _an


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("camfollower.plot needs matplotlib: pip install 'camfollower[plot]'") from e
    return plt


def _theta(points: int) -> np.ndarray:
    if not (isinstance(points, int) and not isinstance(points, bool) and 8 <= points <= _core.MAX_POINTS):
        raise ValueError(f"points must be an integer in [8, {_core.MAX_POINTS}], got {points!r}")
    return np.linspace(0.0, 2 * math.pi, points)


def per_revolution(angle, *series):
    """Fold a recorded angle (rad, cumulative: any revolution) onto one revolution: returns the angle
    in degrees in [0, 360] and each series, ready to plot. Where the angle wraps, the line is closed
    at 360° and restarted at 0° (the series interpolated there) with a NaN between, so no line runs
    back across the plot, e.g. for a periodic orbit whose rows hold both t = 0 and t = T."""
    deg = np.degrees(np.asarray(angle, dtype=float))
    ys = [np.asarray(y, dtype=float) for y in series]
    rev = np.floor(deg / 360.0)
    x = deg - 360.0 * rev
    xs, yss, start = [], [[] for _ in ys], 0
    for i in np.nonzero(np.diff(rev))[0]:
        xs.append(x[start : i + 1])
        for out, y in zip(yss, ys):
            out.append(y[start : i + 1])
        if rev[i + 1] == rev[i] + 1:  # one wrap forward: close the line at the edges
            f = (360.0 * rev[i + 1] - deg[i]) / (deg[i + 1] - deg[i])
            xs.append(np.array([360.0, np.nan, 0.0]))
            for out, y in zip(yss, ys):
                edge = y[i] + f * (y[i + 1] - y[i])
                out.append(np.array([edge, np.nan, edge]))
        else:  # backwards or a skipped revolution: only break the line
            xs.append(np.array([np.nan]))
            for out in yss:
                out.append(np.array([np.nan]))
        start = i + 1
    xs.append(x[start:])
    for out, y in zip(yss, ys):
        out.append(y[start:])
    return (np.concatenate(xs), *(np.concatenate(out) for out in yss))


def svaj(program, rpm: Optional[float] = None, points: int = 3601, axes=None, angular: bool = False):
    """Lift, velocity, acceleration and jerk over one revolution. Per radian of cam angle, or, with
    ``rpm``, in time at that constant camshaft speed. The lift is a length (drawn in mm; m/s, m/s²,
    m/s³ in time), or with ``angular=True`` an oscillating follower's arm rotation (drawn in deg;
    rad/s, rad/s², rad/s³ in time)."""
    plt = _pyplot()
    theta = _theta(points)
    d = program.evaluate(theta)
    w = 1.0
    if rpm is not None:
        if not (math.isfinite(rpm) and rpm > 0):
            raise ValueError(f"rpm must be finite and > 0, got {rpm!r}")
        w = rpm * 2 * math.pi / 60
    if axes is None:
        fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 9))
    fig = axes[0].figure
    base = "rad" if angular else "m"
    per = ("s", "s²", "s³") if rpm is not None else ("rad", "rad²", "rad³")
    units = [f"{base}/{p}" for p in per]
    lift = (np.degrees(d["h"]), "arm rotation h (deg)") if angular else (1e3 * d["h"], "lift h (mm)")
    series = [
        lift,
        (w * d["dh"], f"velocity ({units[0]})"),
        (w**2 * d["d2h"], f"acceleration ({units[1]})"),
        (w**3 * d["d3h"], f"jerk ({units[2]})"),
    ]
    for ax, (y, label) in zip(axes, series):
        ax.plot(np.degrees(theta), y, lw=1.0)
        ax.set_ylabel(label), ax.grid(alpha=0.3)
    axes[-1].set_xlabel("cam angle θ (deg)"), axes[-1].set_xlim(0, 360)
    fig.suptitle("SVAJ" + (f" at {rpm:g} rpm" if rpm is not None else ""))
    return fig


def profile(follower, program, theta: float = 0.0, points: int = 1441, ax=None):
    """The cam surface and the follower's reference curve (a roller's pitch curve) in the cam frame
    (mm), and the contact point at cam angle ``theta`` (rad)."""
    plt = _pyplot()
    t = _theta(points)
    p = follower.profile(program, t)
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(1e3 * p["surface_x"], 1e3 * p["surface_y"], lw=1.2, label="cam surface")
    ax.plot(1e3 * p["reference_x"], 1e3 * p["reference_y"], "--", lw=0.8, label="reference (pitch) curve")
    at = follower.profile(program, np.array([theta]))
    ax.plot(1e3 * at["surface_x"], 1e3 * at["surface_y"], "o", label=f"contact at θ = {math.degrees(theta):.1f}°")
    ax.plot([0], [0], "k+", ms=10, label="cam centre")
    ax.set_aspect("equal"), ax.set_xlabel("x (mm, cam frame)"), ax.set_ylabel("y (mm, cam frame)")
    ax.legend(loc="best", fontsize=8), ax.grid(alpha=0.3)
    # An undercut (or cusped) cam is drawn for inspection, flagged in the title rather than refused.
    try:
        follower.check(program)
        ax.set_title(type(follower).__name__)
    except ValueError as e:
        ax.set_title(f"{type(follower).__name__}: NOT FOLLOWABLE\n{e}", color="tab:red", fontsize=8)
    return ax.figure


def groove(follower, program, clearance: float = 0.0, roller: str = "cylindrical", points: int = 1441, axes=None):
    """A barrel cam's groove, developed: both flanks at the top and bottom radii and the roller centre
    (position round the cam in deg against height along the cam axis in mm), over the pressure angle
    on the lifting flank at the top, pitch and bottom radii (deg), for a ``roller`` "cylindrical" or
    "tapered" and a groove ``clearance`` (m)."""
    from . import export

    plt = _pyplot()
    g = export.groove_points(follower, program, points=points, clearance=clearance, roller=roller)
    if axes is None:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(9, 6.5), height_ratios=(3, 2))
    ax = axes[0]
    styles = ((0, "top", "-", "tab:blue"), (2, "bottom", "--", "tab:orange"))
    for i, where, ls, color in styles:
        r = 1e3 * g["radii"][i]
        for flank in ("lift", "back"):
            ax.plot(
                np.degrees(g[f"{flank}_angle"][i]),
                1e3 * g[f"{flank}_z"][i],
                ls,
                color=color,
                lw=1.0,
                label=f"{where} (r = {r:g} mm)" if flank == "lift" else None,
            )
    ax.plot(np.degrees(g["centre_angle"]), 1e3 * g["centre_z"], ":", color="0.3", lw=0.9, label="roller centre")
    ax.set_ylabel("height along the cam axis (mm)"), ax.grid(alpha=0.3), ax.legend(loc="best", fontsize=8)
    ax.set_title(f"{type(follower).__name__}: developed groove, {roller} roller, clearance {1e3 * clearance:g} mm")
    for i, where, ls, color in (
        (0, "top", "-", "tab:blue"),
        (1, "pitch", "-.", "0.3"),
        (2, "bottom", "--", "tab:orange"),
    ):
        axes[1].plot(np.degrees(g["theta"]), np.degrees(g["pressure_angle"][i]), ls, color=color, lw=1.0, label=where)
    axes[1].set_ylabel("pressure angle (deg)"), axes[1].grid(alpha=0.3), axes[1].legend(loc="best", fontsize=8)
    axes[1].set_xlabel("position round the cam / cam angle θ (deg)"), axes[1].set_xlim(0, 360)
    return axes[0].figure


def pressure_angle_and_curvature(follower, program, points: int = 3601, axes=None):
    """Pressure angle (deg) and surface radius of curvature (mm; concave < 0). Radii beyond ±10 r_b
    (near-straight flanks, where the radius passes through infinity between convex and concave) are
    left as a gap, not drawn at the limit: the limit is marked by dotted lines."""
    plt = _pyplot()
    t = _theta(points)
    p = follower.profile(program, t)
    if axes is None:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    axes[0].plot(np.degrees(t), np.degrees(p["pressure_angle"]), lw=1.0)
    axes[0].set_ylabel("pressure angle (deg)")
    base = getattr(follower, "base_radius", None)
    size, symbol = (base, "r_b") if base is not None else (follower.cylinder_radius, "R")  # a barrel's cylinder
    limit = 10 * size
    rho = np.asarray(p["surface_radius"], dtype=float)
    shown = np.where(np.abs(rho) <= limit, rho, np.nan)  # a gap: no plateau that reads as a value
    axes[1].plot(np.degrees(t), 1e3 * shown, lw=1.0, label="surface radius")
    # The limit is marked on the side(s) where the radius goes beyond it.
    beyond = [sign for sign in (1, -1) if np.any(sign * rho > limit)]
    for i, sign in enumerate(beyond):
        axes[1].axhline(
            sign * 1e3 * limit,
            color="0.3",
            lw=0.8,
            ls=":",
            label=f"display limit ±10 {symbol} = ±{1e3 * limit:g} mm; beyond it: gap" if i == 0 else None,
        )
    if beyond:
        axes[1].legend(loc="best", fontsize=7)
    axes[1].set_ylabel("surface radius of curvature (mm)\nconvex > 0, concave < 0")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("cam angle θ (deg)"), axes[-1].set_xlim(0, 360)
    return axes[0].figure


def acceleration(
    result,
    program,
    omega: float,
    dof: str,
    revolutions: Optional[float] = None,
    ax=None,
    phase: float = 0.0,
    unit: str = "m/s²",
    speed_program=None,
):
    """A follower DOF's simulated acceleration a.<dof> against the rigid-follower ω²h″ (``unit``:
    m/s², rad/s² for an oscillating follower's arm), over the recorded run (or its last
    ``revolutions``), against the cam's own angle: the shaft angle of channel ``theta`` plus the
    contact's ``phase`` (rad), folded onto 0-360° whatever revolutions were recorded (each recorded
    revolution over the same axis, the line broken where the angle wraps). With a variable-speed
    ``speed_program`` (the mechanism's) against time instead, the rigid one h″θ′² + h′θ″."""
    plt = _pyplot()
    t = np.asarray(result["t"])
    a = np.asarray(result[f"a.{dof}"])
    theta = np.asarray(result["theta"])
    if revolutions is not None:
        keep = t >= t[-1] - revolutions * 2 * math.pi / omega
        t, a, theta = t[keep], a[keep], theta[keep]
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    if speed_program is not None and not speed_program.constant_speed:
        drive = speed_program.evaluate(t)
        m = program.evaluate(drive["angle"] + phase)
        rigid = np.asarray(m["d2h"]) * drive["speed"] ** 2 + np.asarray(m["dh"]) * drive["acceleration"]
        ax.plot(t, a, lw=0.8, label=f"simulated a.{dof}")
        ax.plot(t, rigid, "k--", lw=0.8, label="rigid h″θ′² + h′θ″")
        ax.set_xlabel("time (s)"), ax.set_ylabel(f"acceleration ({unit})"), ax.set_xlim(t[0], t[-1])
        ax.legend(loc="best"), ax.grid(alpha=0.3)
        return ax.figure
    deg, a = per_revolution(theta + phase, a)
    ax.plot(deg, a, lw=0.8, label=f"simulated a.{dof}")
    grid = _theta(3601)  # the rigid follower on its own grid: one revolution, drawn once
    ax.plot(np.degrees(grid), omega**2 * np.asarray(program.evaluate(grid)["d2h"]), "k--", lw=0.8, label="rigid ω²h″")
    ax.set_xlabel("cam angle θ (deg, per revolution)"), ax.set_ylabel(f"acceleration ({unit})"), ax.set_xlim(0, 360)
    ax.legend(loc="best"), ax.grid(alpha=0.3)
    return ax.figure


def contact_force(result, contact: str = "cam", ax=None):
    """A contact's force (N) against time, with its intervals without contact (checked at every
    step, ``result.contact_loss``) shaded."""
    plt = _pyplot()
    t = np.asarray(result["t"])
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.plot(t, np.asarray(result[f"{contact}.force"]), lw=0.8, label=f"{contact} force")
    for i, (a, b) in enumerate(result.contact_loss.get(contact, [])):
        ax.axvspan(a, b, color="tab:red", alpha=0.25, lw=0, label="contact lost" if i == 0 else None)
    ax.set_xlabel("time (s)"), ax.set_ylabel("contact force (N)"), ax.legend(loc="best"), ax.grid(alpha=0.3)
    return ax.figure


def spectrum(
    signal,
    sample_rate: float,
    fmax: Optional[float] = None,
    natural_frequencies: Sequence[float] = (),
    ax=None,
    log: bool = True,
    quantity: str = "signal",
    unit: str = "signal units",
):
    """Amplitude spectrum (Hann window) of a signal sampled at ``sample_rate`` (Hz), natural
    frequencies marked; the amplitude axis names the ``quantity`` and its ``unit`` (e.g. "contact
    force", "N"): a sinusoid of amplitude A reads A."""
    plt = _pyplot()
    s = _an.spectrum(np.asarray(signal), sample_rate)
    band = s.band(0.0, fmax if fmax is not None else s.frequency[-1])
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    (ax.semilogy if log else ax.plot)(band.frequency, band.amplitude, lw=0.8, label=quantity)
    marked = [f for f in natural_frequencies if f <= band.frequency[-1]]
    for i, f in enumerate(marked):
        ax.axvline(f, color="tab:red", lw=0.5, ls=":", label="natural frequencies" if i == 0 else None)
    ax.set_xlabel("frequency (Hz)"), ax.set_ylabel(f"{quantity} amplitude ({unit})"), ax.grid(alpha=0.3)
    ax.set_xlim(0, band.frequency[-1])
    ax.set_title(f"Amplitude spectrum of the {quantity} (Hann window)")
    if marked:
        ax.legend(loc="upper right", fontsize=8)
    return ax.figure


__all__ = [
    "per_revolution",
    "svaj",
    "profile",
    "groove",
    "pressure_angle_and_curvature",
    "acceleration",
    "contact_force",
    "spectrum",
]
