# SPDX-License-Identifier: BSD-3-Clause
"""The grooved indexing cam of examples/grooved_cam.toml: its second revolution at 600 cycles/min,
the load on each flank against the cam angle with every strike marked, and the rigid check's
outer-flank intervals shaded. Writes grooved_cam.png (or the path given) and prints the strikes.

Run: .venv/bin/python examples/grooved_cam.py [out.png]
"""

import math
import sys
from pathlib import Path

import camfollower as cf
import numpy as np
from camfollower.analysis import groove_statistics
from camfollower.config import force_closure

CONFIG = Path(__file__).with_name("grooved_cam.toml")


def run():
    case = cf.load_config(CONFIG)
    mech = case.mechanism
    # Every output row 2.5 us apart (the strikes last ~0.1 ms): impact velocities from the rows are close.
    r = cf.simulate(mech, case.settings.replace(time_step=mech.period / 40000), revolutions=2, record_from=mech.period)
    stats = groove_statistics(r, "cam", mech.period)
    return case, mech, r, stats


def plot(case, mech, r, stats, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    deg = np.degrees(np.mod(r["theta"], 2 * math.pi))
    order = np.argsort(deg)
    fig, (ax, ax_lift) = plt.subplots(2, 1, figsize=(9, 6), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    for a, b in force_closure(case.builder)["contacts"][0]["outer_flank_deg"]:
        ax.axvspan(a, b, color="0.9", zorder=0)
    ax.plot(deg[order], r["cam.force"][order], lw=0.8, label="inner flank")
    ax.plot(deg[order], -r["cam.outer_force"][order], lw=0.8, label="outer flank (drawn negative)")
    for t, flank, _ in stats["strikes"]:
        x = math.degrees((mech.omega * t) % (2 * math.pi))
        ax.plot(x, 0.0, "v" if flank == "inner" else "^", ms=4, color="C3" if flank == "outer" else "C2")
    ax.set_ylabel("flank contact force (N)")
    ax.set_title(
        f"Grooved cam at {mech.camshaft_speed_rpm:.0f} rpm: {stats['flank_changes_per_revolution']:.0f} flank changes, "
        f"{stats['impacts_per_revolution']:.0f} strikes per revolution (markers); grey: outer flank carries (rigid)",
        fontsize=9,
    )
    ax.legend(loc="lower left", fontsize=8)
    ax.grid(alpha=0.3)
    ax_lift.plot(deg[order], 1e3 * r["q.carrier"][order], color="k", lw=0.8)
    ax_lift.set_ylabel("carrier (mm)")
    ax_lift.set_xlabel("cam angle (deg)")
    ax_lift.set_xlim(0, 360)
    ax_lift.set_xticks(range(0, 361, 30))
    ax_lift.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def main(out="grooved_cam.png"):
    case, mech, r, stats = run()
    plot(case, mech, r, stats, out)
    print(
        f"{len(stats['strikes'])} strikes, {stats['flank_changes_per_revolution']:.0f} flank changes per revolution, "
        f"fastest strike {stats['max_impact_velocity_m_s']:.3f} m/s, free flight "
        f"{1e3 * stats['free_flight_time_per_revolution_s']:.2f} ms per revolution, peak outer flank force "
        f"{stats['peak_outer_force_N']:.0f} N -> {out}"
    )
    return stats


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "grooved_cam.png")
