# SPDX-License-Identifier: BSD-3-Clause
"""What a periodic steady state costs, side by side: the shooting's monodromy from the step
sensitivities (one variational revolution) against forward differences (2n revolutions), and
optionally against another installed camfollower (an earlier release) in the same run.

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


def run(accuracy, speeds, monodromy):
    """One sweep at `accuracy`; monodromy None: the installed package as it is."""
    import camfollower as cf
    from camfollower import response

    if monodromy is not None:
        response.periodic_steady_state = functools.partial(cf.periodic_steady_state, monodromy=monodromy)
    system = cf.presets.paper()
    rows, guess = [], None
    for rpm in speeds:
        m = system.with_camshaft_speed_rpm(rpm)
        t0 = time.perf_counter()
        row = response.steady_response(m, accuracy=accuracy, guess=guess, multipliers=False, keep_orbit=True)
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
    accuracy, monodromy, speeds = float(argv[0]), argv[1], [float(s) for s in argv[2:]]
    print(json.dumps(run(accuracy, speeds, None if monodromy == "-" else monodromy)))
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
    variants = [("finite differences", None, "differences"), ("variational", None, "variational")]
    if args.baseline:
        variants.insert(0, (f"baseline ({args.baseline})", args.baseline, "-"))
    print(f"paper preset, speeds {args.speeds} rpm; load average {os.getloadavg()[0]:.2f} (2 cores)")
    results = {}
    for _ in range(args.rounds):
        for accuracy in args.accuracy:
            for name, path, monodromy in variants:
                env = dict(os.environ)
                if path:
                    env["PYTHONPATH"] = path
                out = subprocess.run(
                    [sys.executable, __file__, "--child", str(accuracy), monodromy, *map(str, args.speeds)],
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
        for name, _, _ in variants:
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
