# SPDX-License-Identifier: BSD-3-Clause
"""Plots for any cam and any result (matplotlib, an optional extra: ``pip install camfollower[plot]``).

Every function draws into new axes (or the ``ax``/``axes`` given) and returns the Figure, so it can
be saved, shown or changed. Angles are shown in degrees, lengths in mm; the data stay SI.

- :func:`svaj`: lift, velocity, acceleration and jerk of a motion program;
- :func:`profile`: the cam surface, the follower's reference curve (a roller's pitch curve) and the
  contact point at one cam angle; an undercut cam is drawn and flagged in the title, not refused;
- :func:`pressure_angle_and_curvature`: both along the revolution;
- :func:`acceleration`: a follower DOF's simulated acceleration against the rigid ω²h″;
- :func:`contact_force`: a contact's force with its intervals without contact shaded;
- :func:`spectrum`: an amplitude spectrum with natural frequencies marked.
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


def svaj(program, rpm: Optional[float] = None, points: int = 3601, axes=None):
    """Lift (mm), velocity, acceleration and jerk over one revolution. Per radian of cam angle, or,
    with ``rpm``, in time (m/s, m/s², m/s³) at that constant camshaft speed."""
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
    units = ("m/s", "m/s²", "m/s³") if rpm is not None else ("m/rad", "m/rad²", "m/rad³")
    series = [(1e3 * d["h"], "lift h (mm)"), (w * d["dh"], f"velocity ({units[0]})"),
              (w**2 * d["d2h"], f"acceleration ({units[1]})"), (w**3 * d["d3h"], f"jerk ({units[2]})")]
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


def pressure_angle_and_curvature(follower, program, points: int = 3601, axes=None):
    """Pressure angle (deg) and surface radius of curvature (mm; concave < 0, clipped to ±10 r_b)."""
    plt = _pyplot()
    t = _theta(points)
    p = follower.profile(program, t)
    if axes is None:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    axes[0].plot(np.degrees(t), np.degrees(p["pressure_angle"]), lw=1.0)
    axes[0].set_ylabel("pressure angle (deg)")
    limit = 10 * follower.base_radius
    rho = np.clip(np.asarray(p["surface_radius"]), -limit, limit)
    axes[1].plot(np.degrees(t), 1e3 * rho, lw=1.0)
    axes[1].set_ylabel("surface radius of curvature (mm)")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("cam angle θ (deg)"), axes[-1].set_xlim(0, 360)
    return axes[0].figure


def acceleration(result, program, omega: float, dof: str, revolutions: Optional[float] = None, ax=None):
    """A follower DOF's simulated acceleration a.<dof> against the rigid-follower ω²h″ (m/s²), over
    the recorded run (or its last ``revolutions``), against the cam angle of channel ``theta``."""
    plt = _pyplot()
    t = np.asarray(result["t"])
    a = np.asarray(result[f"a.{dof}"])
    theta = np.asarray(result["theta"])
    if revolutions is not None:
        keep = t >= t[-1] - revolutions * 2 * math.pi / omega
        a, theta = a[keep], theta[keep]
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    deg = np.degrees(theta)
    ax.plot(deg, a, lw=0.8, label=f"simulated a.{dof}")
    ax.plot(deg, omega**2 * np.asarray(program.evaluate(theta)["d2h"]), "k--", lw=0.8, label="rigid ω²h″")
    ax.set_xlabel("cam angle θ (deg, cumulative)"), ax.set_ylabel("acceleration (m/s²)")
    ax.legend(loc="best"), ax.grid(alpha=0.3)
    return ax.figure


def contact_force(result, contact: str = "cam", ax=None):
    """A contact's force (N) against time, with its intervals without contact (checked at every
    step, ``result.contact_loss``) shaded."""
    plt = _pyplot()
    t = np.asarray(result["t"])
    name = f"{contact}.force" if f"{contact}.force" in result else "contact_force"
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.plot(t, np.asarray(result[name]), lw=0.8, label=f"{contact} force")
    for i, (a, b) in enumerate(result.contact_loss.get(contact, [])):
        ax.axvspan(a, b, color="tab:red", alpha=0.25, lw=0, label="contact lost" if i == 0 else None)
    ax.set_xlabel("time (s)"), ax.set_ylabel("contact force (N)"), ax.legend(loc="best"), ax.grid(alpha=0.3)
    return ax.figure


def spectrum(signal, sample_rate: float, fmax: Optional[float] = None,
             natural_frequencies: Sequence[float] = (), ax=None, log: bool = True):
    """Amplitude spectrum (Hann window) of a signal sampled at ``sample_rate`` (Hz), natural
    frequencies marked."""
    plt = _pyplot()
    s = _an.spectrum(np.asarray(signal), sample_rate)
    band = s.band(0.0, fmax if fmax is not None else s.frequency[-1])
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    (ax.semilogy if log else ax.plot)(band.frequency, band.amplitude, lw=0.8)
    for f in natural_frequencies:
        if f <= band.frequency[-1]:
            ax.axvline(f, color="tab:red", lw=0.5, ls=":")
    ax.set_xlabel("frequency (Hz)"), ax.set_ylabel("amplitude"), ax.grid(alpha=0.3)
    return ax.figure


__all__ = ["svaj", "profile", "pressure_angle_and_curvature", "acceleration", "contact_force", "spectrum"]
