# SPDX-License-Identifier: BSD-3-Clause
"""Monte-Carlo benchmark (docs/benchmarks.md, "Design studies"): 1,000 tolerance cases of the paper
preset to the periodic steady state through a Dask LocalCluster (2 worker processes), cases/s against
the same study run serially, worker memory before and after, and the shooting route against the
transient route at equal steady-state accuracy.

    .venv/bin/python bench/montecarlo.py [--cases 1000] [--serial-cases 200]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import camfollower as cf
from camfollower import tolerance as tol

TOLERANCES = {"contact_stiffness": tol.Normal(0.05, relative=True),
              "spring_stiffness": tol.Uniform(-0.05, 0.05, relative=True),
              "spring_preload_deflection": tol.TruncatedNormal(0.3e-3, -0.5e-3, 0.5e-3),
              "eccentricity": tol.TruncatedNormal(5e-6, 0.0, 20e-6)}
STEPS = 4096


def rss_mib() -> float:
    import psutil

    return psutil.Process().memory_info().rss / 2 ** 20


def study(cases, executor):
    t0 = time.perf_counter()
    r = tol.monte_carlo(tol.PaperCase(), TOLERANCES, cases=cases, seed=7, executor=executor, progress=False)
    return r, time.perf_counter() - t0


def shooting_vs_transient(m, accuracy=1e-6):
    """Wall time of the shooting route and of the transient route (revolutions from rest until the
    state at the revolution's start stays within `accuracy` of the orbit, relative to the largest
    |q| and |v| on it). The transient of the lightly damped paper mechanism wanders about the orbit at
    ~2e-8 (rounding keeps exciting its 3 %-per-revolution mode), hence 1e-6."""
    dt = m.period / STEPS
    t0 = time.perf_counter()
    o = cf.periodic_steady_state(m, time_step=dt, multipliers=False)  # tolerance 1e-9
    t_shoot = time.perf_counter() - t0
    ref = cf.periodic_steady_state(m, time_step=dt, tolerance=1e-11)
    t0 = time.perf_counter()
    r = cf.simulate(m, revolutions=3000, time_step=dt, decimation=STEPS)
    t_all = time.perf_counter() - t0
    q, v = np.asarray(r.q), np.asarray(r.v)
    # relative to the largest |q| (the lift) and |v| over the revolution, as the shooting measures it
    err = np.maximum(np.abs(q - ref.q).max(axis=1) / ref.q_scale, np.abs(v - ref.v).max(axis=1) / ref.v_scale)
    inside = np.flatnonzero(err > accuracy)
    revs = int(inside[-1] + 1) if inside.size else 0
    t_transient = t_all * revs / 3000
    return {"shooting_s": t_shoot, "shooting_revolutions": o.revolutions, "transient_revolutions": revs,
            "transient_s": t_transient, "ratio": t_transient / t_shoot, "spectral_radius": ref.spectral_radius}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--serial-cases", type=int, default=200)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores)")
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        study(20, client)  # warm the workers (imports)
        before = client.run(rss_mib)
        r, t_dask = study(args.cases, client)
        after = client.run(rss_mib)
    failed = len(r.failed())
    print(f"Dask LocalCluster, 2 workers: {args.cases} cases in {t_dask:.1f} s = {args.cases / t_dask:.1f} cases/s "
          f"({failed} failed)")
    print("worker memory (MiB) before -> after: " + ", ".join(f"{before[k]:.0f} -> {after[k]:.0f}" for k in before))
    _, t_serial = study(args.serial_cases, "serial")
    serial_rate = args.serial_cases / t_serial
    print(f"serial: {args.serial_cases} cases in {t_serial:.1f} s = {serial_rate:.1f} cases/s; "
          f"Dask / serial = {args.cases / t_dask / serial_rate:.2f}")
    revs = np.array([row["revolutions"] for row in r.rows if row["ok"]])
    print(f"revolutions per case: median {np.median(revs):.0f}, mean {revs.mean():.1f}, max {revs.max():.0f}")
    for name, m in (("paper", cf.presets.paper()), ("paper_damped", cf.presets.paper_damped())):
        c = shooting_vs_transient(m)
        print(f"{name}: to 1e-6 of the orbit, shooting {c['shooting_s'] * 1e3:.1f} ms ({c['shooting_revolutions']:.0f} "
              f"revolutions), transient {c['transient_s'] * 1e3:.1f} ms ({c['transient_revolutions']} revolutions): "
              f"transient / shooting = {c['ratio']:.2f} (spectral radius {c['spectral_radius']:.4f})")


if __name__ == "__main__":
    main()
