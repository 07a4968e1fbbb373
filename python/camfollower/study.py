"""The paper's study, run as ``python -m camfollower.study`` (or ``camfollower-study``).

Writes to the output folder (default ``out/``): the cam kinematics figure and data, the cam surface
as CSV, and ``summary.json``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

from . import DiskCam


def kinematics_summary(cam: DiskCam, rpm: float) -> dict:
    """Pressure-angle extremes, tightest cam-surface radius and peak follower acceleration."""
    omega = rpm * 2 * math.pi / 60
    theta = np.linspace(0, 2 * math.pi, 360001)
    d2h = cam.program.evaluate(theta)["d2h"]
    k = int(np.argmax(np.abs(d2h)))
    t_rise, a_rise = cam.max_pressure_angle_rise()
    t_ret, a_ret = cam.max_pressure_angle_return()
    t_rho, rho = cam.min_surface_radius()
    return {
        "rpm": rpm,
        "period_s": 60.0 / rpm,
        "max_pressure_angle_rise_deg": math.degrees(a_rise),
        "max_pressure_angle_rise_at_deg": math.degrees(t_rise),
        "max_pressure_angle_return_deg": math.degrees(a_ret),
        "max_pressure_angle_return_at_deg": math.degrees(t_ret),
        "min_surface_radius_m": rho,
        "min_surface_radius_at_deg": math.degrees(t_rho),
        "max_theoretical_follower_acceleration_m_s2": float(omega**2 * abs(d2h[k])),
        "max_theoretical_follower_acceleration_at_deg": math.degrees(theta[k]),
    }


def plot_kinematics(cam: DiskCam, rpm: float, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    omega = rpm * 2 * math.pi / 60
    theta = np.linspace(0, 2 * math.pi, 3601)
    p = cam.profile(theta)
    h = cam.program.evaluate(theta)
    deg = np.degrees(theta)
    fig = plt.figure(figsize=(11, 7))
    ax = [fig.add_subplot(2, 3, i) for i in (1, 2, 4, 5)] + [fig.add_subplot(1, 3, 3)]
    ax[0].plot(deg, 1e3 * h["h"]), ax[0].set_ylabel("lift h (mm)")
    ax[1].plot(deg, omega * h["dh"]), ax[1].set_ylabel("follower velocity (m/s)")
    ax[2].plot(deg, omega**2 * h["d2h"]), ax[2].set_ylabel("follower acceleration (m/s²)")
    ax[3].plot(deg, np.degrees(p["pressure_angle"])), ax[3].set_ylabel("pressure angle (deg)")
    for a in ax[:4]:
        a.set_xlabel("cam angle θ (deg)"), a.set_xlim(0, 360), a.grid(alpha=0.3)
    ax[4].plot(1e3 * p["surface_x"], 1e3 * p["surface_y"], label="cam surface")
    ax[4].plot(1e3 * p["pitch_x"], 1e3 * p["pitch_y"], "--", label="pitch curve")
    ax[4].set_aspect("equal"), ax[4].set_xlabel("x (mm)"), ax[4].set_ylabel("y (mm)"), ax[4].legend()
    fig.suptitle(f"Paper cam kinematics at {rpm:g} rpm (modified trapezoid, e = {1e3 * cam.offset:g} mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def atomic_write_text(path: Path, text: str) -> None:
    """Write via a temporary file and rename, so a failure never leaves a complete-looking file."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="camfollower-study", description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out", help="output folder (created if missing); default: out")
    parser.add_argument("--rpm", type=float, default=750.0, help="camshaft speed in rpm; default: 750")
    args = parser.parse_args(argv)
    if not (math.isfinite(args.rpm) and args.rpm > 0):
        parser.error(f"--rpm must be a finite number > 0, got {args.rpm}")
    out = Path(args.out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        probe = out / ".write-test"
        probe.write_text("")
        probe.unlink()
    except OSError as e:
        parser.error(f"--out: cannot write to '{out}': {e.strerror}")

    cam = DiskCam()
    summary = {"kinematics": kinematics_summary(cam, args.rpm)}
    for key, value in summary["kinematics"].items():
        print(f"{key:48s} {value:.6g}")
    plot_kinematics(cam, args.rpm, out / "kinematics.png")
    cam.write_surface_csv(str(out / "cam_surface.csv"))
    atomic_write_text(out / "summary.json", json.dumps(summary, indent=2) + "\n")
    print(f"wrote {out}/kinematics.png, cam_surface.csv, summary.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
