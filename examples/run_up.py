# SPDX-License-Identifier: BSD-3-Clause
"""The run-up of examples/run_up.toml: a grooved indexing cam brought from standstill to 600 cycles/min
in 0.4 s, its swing arm driving a slide through a coupler. Against time: the camshaft speed, the torque
the cam takes from the camshaft (what the motor must give), the load on each flank of the groove, and
the slide's acceleration against the rigid linkage's. Writes run_up.png (or the path given).

Run: .venv/bin/python examples/run_up.py [out.png]
"""

import math
import sys
from pathlib import Path

import camfollower as cf
import numpy as np

CONFIG = Path(__file__).with_name("run_up.toml")


def run():
    case = cf.load_config(CONFIG)
    return case, case.mechanism, cf.simulate(case.mechanism, case.settings, case.options)


def rigid_slide_acceleration(mech, r):
    """The slide's acceleration if everything were rigid: the linkage's output SVAJ on the cam's lift,
    s'' theta'^2 + s' theta'' at the camshaft's speed and acceleration."""
    builder = mech.builder()
    link, program = builder.linkages[0], builder.contacts[0]["program"]
    drive = mech.speed_program.evaluate(r.t)
    svaj = link.svaj(program, np.mod(drive["angle"], 2 * math.pi))
    return svaj["d2s"] * drive["speed"] ** 2 + svaj["ds"] * drive["acceleration"]


def plot(mech, r, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = r.t
    fig, (ax_w, ax_t, ax_f, ax_a) = plt.subplots(4, 1, figsize=(9, 9.5), sharex=True)
    ax_w.plot(t, r["drive.speed"] * 30 / math.pi, lw=1.0)
    ax_w.set_ylabel("camshaft speed (rpm)")
    ax_w.set_title(
        f"Run-up of a grooved indexing cam to {mech.camshaft_speed_rpm:.0f} cycles/min in "
        f"{mech.speed_program.ramps[0].duration:g} s",
        fontsize=10,
    )
    ax_t.plot(t, r["drive.torque"], lw=0.6)
    ax_t.set_ylabel("drive torque (N m)")
    ax_f.plot(t, r["cam.force"], lw=0.6, label="inner flank")
    ax_f.plot(t, r["cam.outer_force"], lw=0.6, label="outer flank")
    ax_f.set_ylabel("contact force (N)")
    ax_f.legend(loc="upper left", fontsize=8)
    ax_a.plot(t, r["a.slide"], lw=0.6, label="slide (simulated)")
    ax_a.plot(t, rigid_slide_acceleration(mech, r), "k--", lw=0.7, label="rigid linkage: s''θ′² + s'θ″")
    ax_a.set_ylabel("slide acceleration (m/s²)")
    ax_a.set_xlabel("time (s)")
    ax_a.legend(loc="upper left", fontsize=8)
    for ax in (ax_w, ax_t, ax_f, ax_a):
        ax.grid(alpha=0.3)
        ax.set_xlim(t[0], t[-1])
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def main(out="run_up.png"):
    case, mech, r = run()
    plot(mech, r, out)
    at_speed = r.t >= mech.speed_program.ramps[0].duration
    work = float(np.sum(0.5 * (r["drive.power"][1:] + r["drive.power"][:-1]) * np.diff(r.t)))
    summary = {
        "peak_torque_N_m": float(np.abs(r["drive.torque"]).max()),
        "peak_torque_at_speed_N_m": float(np.abs(r["drive.torque"][at_speed]).max()),
        "peak_power_W": float(np.abs(r["drive.power"]).max()),
        "drive_work_J": work,
        "outer_flank_peak_N": float(r["cam.outer_force"].max()),
    }
    print(
        f"peak drive torque {summary['peak_torque_N_m']:.2f} N m ({summary['peak_torque_at_speed_N_m']:.2f} at "
        f"speed), peak power {summary['peak_power_W']:.0f} W, work {work:.2f} J -> {out}"
    )
    return summary


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "run_up.png")
