# SPDX-License-Identifier: BSD-3-Clause
"""Monte-Carlo transients on C++ threads (docs/benchmarks.md, "Many cases at once"): 1,000 tolerance
cases of the paper preset, 3 revolutions each from the static equilibrium, contact force to ~3e-4,
with simulate_many on 1 and 2 threads; the force error of sample cases against Dormand-Prince at
tolerance 1e-10 on the same output grid.

    .venv/bin/python bench/montecarlo_threads.py [--cases 1000] [--revolutions 3] [--steps 4096]
"""

from __future__ import annotations

import argparse
import os
import time

import camfollower as cf
import numpy as np
from camfollower import tolerance as tol

TOLERANCES = {
    "contact_stiffness": tol.Normal(0.05, relative=True),
    "spring_stiffness": tol.Uniform(-0.05, 0.05, relative=True),
    "spring_preload_deflection": tol.TruncatedNormal(0.3e-3, -0.5e-3, 0.5e-3),
    "eccentricity": tol.TruncatedNormal(5e-6, 0.0, 20e-6),
}


def draw(build, cases: int, seed: int = 7):
    """Case i's values from numpy.random.default_rng([seed, i]), as camfollower.tolerance draws them."""
    nominal = {name: build.nominal(name) for name in TOLERANCES}
    out = []
    for i in range(cases):
        rng = np.random.default_rng([seed, i])
        v = {}
        for name, dist in TOLERANCES.items():
            d = dist.sample(rng)
            v[name] = nominal[name] * (1.0 + d) if dist.relative else nominal[name] + d
        out.append(v)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--revolutions", type=float, default=3.0)
    ap.add_argument("--steps", type=int, default=4096, help="Fox-Goodwin steps per revolution")
    ap.add_argument("--decimation", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores)")
    build = tol.PaperCase()
    t0 = time.perf_counter()
    systems = [build(v) for v in draw(build, args.cases)]
    t_build = time.perf_counter() - t0
    period = systems[0].period
    run = dict(
        revolutions=args.revolutions, time_step=period / args.steps, method="fox_goodwin", decimation=args.decimation
    )
    cf.simulate_many(systems[:8], **run)  # warm up
    times = {1: [], 2: []}
    for _ in range(args.repeats):  # interleaved
        for threads in (1, 2):
            t0 = time.perf_counter()
            results = cf.simulate_many(systems, threads=threads, **run)
            times[threads].append(time.perf_counter() - t0)
    steps = sum(r.stats["steps"] for r in results)
    print(
        f"{args.cases} cases x {args.revolutions:g} revolutions, fox_goodwin T/{args.steps} "
        f"({steps / args.cases:.0f} steps per case), decimation {args.decimation}:"
    )
    print(f"  building the {args.cases} models (Python, calibration + static equilibrium): {t_build:.2f} s")
    for threads, ts in times.items():
        print(
            f"  simulate_many threads={threads}: median {np.median(ts):.2f} s of {', '.join(f'{t:.2f}' for t in ts)}"
            f" ({steps / np.median(ts) / 1e6:.2f} M steps/s)"
        )
    print(f"  threads 2 / 1 speed-up: {np.median(times[1]) / np.median(times[2]):.2f}")
    print(f"  total with building, 2 threads: {t_build + np.median(times[2]):.2f} s")
    # Accuracy of sample cases: contact force against Dormand-Prince at tolerance 1e-10 (its global
    # force error on this model is ~2e-8) on the same rows.
    errors = []
    for i in np.linspace(0, args.cases - 1, 5).astype(int):
        ref = cf.simulate(
            systems[i],
            revolutions=args.revolutions,
            time_step=period / args.steps,
            method="dormand_prince",
            tolerance=1e-10,
            decimation=args.decimation,
        )
        f, f_ref = results[i]["cam.force"], ref["cam.force"]
        errors.append(np.abs(f - f_ref).max() / np.abs(f_ref).max())
    print(
        "  contact force error of cases "
        + ", ".join(f"{e:.1e}" for e in errors)
        + f" (max |F - F_ref| / max |F_ref| over the rows; worst {max(errors):.1e})"
    )


if __name__ == "__main__":
    main()
