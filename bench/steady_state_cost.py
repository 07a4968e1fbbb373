# SPDX-License-Identifier: BSD-3-Clause
"""What a periodic steady state costs today, and where the time goes (the baseline of issue 38's
target: the paper preset's steady state to 1e-6 in force, 5x faster).

For each accuracy (relative error of the contact force and follower acceleration, estimated by
steady_response from orbits at successive step halvings), a margin curve's speeds are found one after
another, each warm-started from the previous speed's orbit as a sweep does. Per speed: wall time,
revolutions simulated, of them the revolutions spent on monodromy matrices (2n each, n DOFs: forward
differences), shooting iterations and the steps per revolution reached.

    .venv/bin/python bench/steady_state_cost.py [--speeds 600 700 800] [--accuracy 1e-4 1e-6]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

import camfollower as cf
from camfollower.response import steady_response


def run(system, speeds, accuracy):
    rows, guess = [], None
    for rpm in speeds:
        m = system.with_camshaft_speed_rpm(rpm)
        t0 = time.perf_counter()
        row = steady_response(m, accuracy=accuracy, guess=guess, multipliers=False, keep_orbit=True)
        seconds = time.perf_counter() - t0
        orbit = row["orbit"]
        guess = orbit
        n = len(m.dof_names)
        rows.append(
            {
                "rpm": rpm,
                "seconds": seconds,
                "revolutions": row["revolutions"],
                "monodromy_revolutions": 2 * n * orbit.monodromies,
                "iterations": orbit.iterations,
                "steps_per_revolution": row["steps_per_revolution"],
                "accuracy": row["accuracy"],
                "reached": row["accuracy_reached"],
            }
        )
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[600.0, 650.0, 700.0, 750.0, 800.0])
    parser.add_argument("--accuracy", type=float, nargs="+", default=[1e-4, 1e-6])
    args = parser.parse_args(argv)
    system = cf.presets.paper()
    print(f"paper preset, {len(system.dof_names)} DOFs; load average {os.getloadavg()[0]:.2f} (2 cores)")
    print(
        "| accuracy | speeds | median s per speed | revolutions per speed | of them monodromy (last orbit) "
        "| iterations (last orbit) | steps per revolution | accuracy reached |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for accuracy in args.accuracy:
        rows = run(system, args.speeds, accuracy)
        print(
            f"| {accuracy:g} | {len(rows)} | {statistics.median(r['seconds'] for r in rows):.3f} | "
            f"{statistics.median(r['revolutions'] for r in rows):.0f} | "
            f"{statistics.median(r['monodromy_revolutions'] for r in rows):.0f} | "
            f"{statistics.median(r['iterations'] for r in rows):.0f} | "
            f"{'/'.join(sorted({str(r['steps_per_revolution']) for r in rows}))} | "
            f"{max(r['accuracy'] for r in rows):.1e} ({'all' if all(r['reached'] for r in rows) else 'NOT all'}) |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
