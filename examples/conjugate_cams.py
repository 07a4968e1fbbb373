# SPDX-License-Identifier: BSD-3-Clause
"""The conjugate cams of examples/conjugate_cams.toml: the second revolution at 600 cycles/min, the
load on each cam against the cam angle with the rigid check's hand-over shaded, and the arm's
acceleration against the rigid one. Writes conjugate_cams.png (or the path given).

Run: .venv/bin/python examples/conjugate_cams.py [out.png]
"""

import math
import sys
from pathlib import Path

import camfollower as cf
import numpy as np
from camfollower.config import force_closure

CONFIG = Path(__file__).with_name("conjugate_cams.toml")


def run():
    case = cf.load_config(CONFIG)
    mech = case.mechanism
    r = cf.simulate(mech, case.settings, revolutions=2, record_from=mech.period)
    return case, mech, r


def plot(case, mech, r, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deg = np.degrees(np.mod(r["theta"], 2 * math.pi))
    order = np.argsort(deg)
    program = case.programs["index"]
    rigid = np.array([mech.omega**2 * program.evaluate(t)["d2h"] for t in np.radians(deg[order])])
    fig, (ax, ax_acc) = plt.subplots(2, 1, figsize=(9, 6), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    lift = force_closure(case.builder)["contacts"][0]
    for a, b in lift["other_cam_deg"]:
        ax.axvspan(a, b, color="0.9", zorder=0)
    ax.plot(deg[order], r["cams.lift.force"][order], lw=0.9, label="lift cam")
    ax.plot(deg[order], r["cams.return.force"][order], lw=0.9, label="return cam")
    ax.set_ylabel("contact force (N)")
    ax.set_title(
        f"Conjugate cams at {mech.camshaft_speed_rpm:.0f} rpm, the rollers preloaded by interference\n"
        f"grey: the return cam carries the net load (rigid check; {lift['flank_changes']} hand-overs per revolution)",
        fontsize=9,
    )
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3)
    ax_acc.plot(deg[order], r["a.arm"][order] / 1e3, lw=0.8, label="arm (flexible)")
    ax_acc.plot(deg[order], rigid / 1e3, "k--", lw=0.8, label="rigid: omega^2 h''")
    ax_acc.set_ylabel("arm acceleration (10^3 rad/s^2)")
    ax_acc.set_xlabel("cam angle (deg)")
    ax_acc.set_xlim(0, 360)
    ax_acc.set_xticks(range(0, 361, 30))
    ax_acc.legend(loc="upper right", fontsize=8)
    ax_acc.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def main(out="conjugate_cams.png"):
    case, mech, r = run()
    plot(case, mech, r, out)
    summary = {
        "min_lift_force_N": float(r["cams.lift.force"].min()),
        "min_return_force_N": float(r["cams.return.force"].min()),
        "max_force_N": float(max(r["cams.lift.force"].max(), r["cams.return.force"].max())),
    }
    print(
        f"lift cam {summary['min_lift_force_N']:.0f} N to {r['cams.lift.force'].max():.0f} N, return cam "
        f"{summary['min_return_force_N']:.0f} N to {r['cams.return.force'].max():.0f} N -> {out}"
    )
    return summary


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "conjugate_cams.png")
