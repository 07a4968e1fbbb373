# SPDX-License-Identifier: BSD-3-Clause
"""What a periodic steady state costs, side by side: the shooting's monodromy from the step
sensitivities (one variational revolution) against forward differences (2n revolutions), the accuracy
of the force and acceleration against the force alone (accuracy_of), and optionally another installed
camfollower (an earlier release, given the force-alone criterion by patching) in the same run.

For each accuracy (relative error of the contact force and follower acceleration, estimated by
steady_response from orbits at successive step halvings), a margin curve's speeds are found one after
another, each warm-started from the previous speed's orbit as a sweep does. The variants run in
interleaved rounds (this machine is shared and noisy); per variant and accuracy: the median over
rounds of the median wall time per speed, the revolutions per speed (of them variational), the steps
per revolution reached and the accuracy reached. Ratios are to the first variant.

    .venv/bin/python bench/steady_state_cost.py [--speeds 600 700 800] [--accuracy 1e-4 1e-6]
        [--rounds 3] [--baseline DIR]   # DIR: a camfollower installed with pip --target DIR
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import statistics
import subprocess
import sys
import time


def run(accuracy, speeds, monodromy, accuracy_of):
    """One sweep at `accuracy` of `accuracy_of` ("force_and_acceleration" or "force"); monodromy None:
    the installed package as it is. A package without accuracy_of (an earlier release) gets the same
    criterion by zeroing the acceleration its estimate compares."""
    import camfollower as cf
    import numpy as np
    from camfollower import response

    if monodromy is not None:
        response.periodic_steady_state = functools.partial(cf.periodic_steady_state, monodromy=monodromy)
    options = {}
    if accuracy_of != "force_and_acceleration":
        if hasattr(response, "ACCURACY_OF"):
            options["accuracy_of"] = accuracy_of
        else:
            measured = response._measured

            def force_only(system, orbit, name, dof):
                force, acc, rec = measured(system, orbit, name, dof)
                return force, np.zeros_like(acc), rec

            response._measured = force_only
    system = cf.presets.paper()
    rows, guess = [], None
    for rpm in speeds:
        m = system.with_camshaft_speed_rpm(rpm)
        t0 = time.perf_counter()
        row = response.steady_response(m, accuracy=accuracy, guess=guess, multipliers=False, keep_orbit=True, **options)
        seconds = time.perf_counter() - t0
        guess = row["orbit"]
        rows.append(
            {
                "seconds": seconds,
                "revolutions": row["revolutions"],
                "steps_per_revolution": row["steps_per_revolution"],
                "accuracy": row["accuracy"],
                "reached": bool(row["accuracy_reached"]),
            }
        )
    return rows


def _child(argv) -> int:
    """Runs one sweep in this process (for a variant on another sys.path) and prints its rows as JSON."""
    accuracy, monodromy, accuracy_of, speeds = float(argv[0]), argv[1], argv[2], [float(s) for s in argv[3:]]
    print(json.dumps(run(accuracy, speeds, None if monodromy == "-" else monodromy, accuracy_of)))
    return 0


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] == "--child":
        return _child(argv[1:])
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[600.0, 650.0, 700.0, 750.0, 800.0])
    parser.add_argument("--accuracy", type=float, nargs="+", default=[1e-4, 1e-6])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--baseline", help="a directory holding another camfollower (pip install --target DIR)")
    args = parser.parse_args(argv)
    both, force = "force_and_acceleration", "force"
    variants = [
        ("finite differences, force and acceleration", None, "differences", both),
        ("variational, force and acceleration", None, "variational", both),
        ("variational, force alone", None, "variational", force),
    ]
    if args.baseline:
        variants = [
            (f"baseline ({args.baseline}), force and acceleration", args.baseline, "-", both),
            (f"baseline ({args.baseline}), force alone", args.baseline, "-", force),
            *variants[1:],
        ]
    print(f"paper preset, speeds {args.speeds} rpm; load average {os.getloadavg()[0]:.2f} (2 cores)")
    results = {}
    for _ in range(args.rounds):
        for accuracy in args.accuracy:
            for name, path, monodromy, accuracy_of in variants:
                env = dict(os.environ)
                if path:
                    env["PYTHONPATH"] = path
                out = subprocess.run(
                    [
                        sys.executable,
                        __file__,
                        "--child",
                        str(accuracy),
                        monodromy,
                        accuracy_of,
                        *map(str, args.speeds),
                    ],
                    env=env,
                    check=True,
                    capture_output=True,
                    text=True,
                ).stdout
                results.setdefault((accuracy, name), []).append(json.loads(out.splitlines()[-1]))
    print(
        "| accuracy | variant | median s per speed | ratio | revolutions per speed | steps per revolution "
        "| accuracy reached |"
    )
    print("|---|---|---|---|---|---|---|")
    for accuracy in args.accuracy:
        first = None
        for name, *_ in variants:
            rounds = results[(accuracy, name)]
            seconds = statistics.median(statistics.median(r["seconds"] for r in rows) for rows in rounds)
            first = first or seconds
            rows = rounds[0]
            print(
                f"| {accuracy:g} | {name} | {seconds:.3f} | {first / seconds:.2f} | "
                f"{statistics.median(r['revolutions'] for r in rows):.0f} | "
                f"{'/'.join(sorted({str(r['steps_per_revolution']) for r in rows}, key=int))} | "
                f"{max(r['accuracy'] for r in rows):.1e} ({'all' if all(r['reached'] for r in rows) else 'NOT all'}) |"
            )
    print(f"load average at the end {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
