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

import camfollower as cf
import numpy as np
from camfollower import tolerance as tol

TOLERANCES = {
    "contact_stiffness": tol.Normal(0.05, relative=True),
    "spring_stiffness": tol.Uniform(-0.05, 0.05, relative=True),
    "spring_preload_deflection": tol.TruncatedNormal(0.3e-3, -0.5e-3, 0.5e-3),
    "eccentricity": tol.TruncatedNormal(5e-6, 0.0, 20e-6),
}
STEPS = 4096


def rss_mib() -> float:
    import psutil

    return psutil.Process().memory_info().rss / 2**20


def study(cases, executor):
    t0 = time.perf_counter()
    r = tol.monte_carlo(tol.PaperCase(), TOLERANCES, cases=cases, seed=7, executor=executor, progress=False)
    return r, time.perf_counter() - t0


def shooting_vs_transient(m, accuracies=(1e-5, 1e-6, 1e-7, 1e-8), horizon=1000):
    """Wall time of the shooting route (default tolerance 1e-9) and, per accuracy, of the transient
    route: the revolutions from rest after which the state at each revolution's start stays within
    the accuracy of the orbit (relative to the largest |q| and |v| on it), timed at the run's rate.
    The transient of the lightly damped paper mechanism scatters about the orbit by a few 1e-8 (its
    3 %-per-revolution mode keeps being excited at rounding level): finer accuracies are not held (None)."""
    dt = m.period / STEPS
    t0 = time.perf_counter()
    o = cf.periodic_steady_state(m, time_step=dt, multipliers=False)
    t_shoot = time.perf_counter() - t0
    ref = cf.periodic_steady_state(m, time_step=dt, tolerance=1e-11)
    t0 = time.perf_counter()
    r = cf.simulate(m, revolutions=horizon, time_step=dt, decimation=STEPS)
    per_revolution = (time.perf_counter() - t0) / horizon
    q, v = np.asarray(r.q), np.asarray(r.v)
    err = np.maximum(np.abs(q - ref.q).max(axis=1) / ref.q_scale, np.abs(v - ref.v).max(axis=1) / ref.v_scale)
    out = {
        "shooting_s": t_shoot,
        "shooting_revolutions": o.revolutions,
        "spectral_radius": ref.spectral_radius,
        "transient": {},
    }
    for acc in accuracies:
        outside = np.flatnonzero(err > acc)
        revs = None if outside.size and outside[-1] >= len(err) - 50 else int(outside[-1] + 1) if outside.size else 0
        out["transient"][acc] = (revs, None if revs is None else revs * per_revolution)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--serial-cases", type=int, default=200)
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores)")
    from distributed import Client, LocalCluster

    with (
        LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):
        study(20, client)  # warm the workers (imports)
        before = client.run(rss_mib)
        r, t_dask = study(args.cases, client)
        after = client.run(rss_mib)
    failed = len(r.failed())
    print(
        f"Dask LocalCluster, 2 workers: {args.cases} cases in {t_dask:.1f} s = {args.cases / t_dask:.1f} cases/s "
        f"({failed} failed)"
    )
    print("worker memory (MiB) before -> after: " + ", ".join(f"{before[k]:.0f} -> {after[k]:.0f}" for k in before))
    _, t_serial = study(args.serial_cases, "serial")
    serial_rate = args.serial_cases / t_serial
    print(
        f"serial: {args.serial_cases} cases in {t_serial:.1f} s = {serial_rate:.1f} cases/s; "
        f"Dask / serial = {args.cases / t_dask / serial_rate:.2f}"
    )
    revs = np.array([row["revolutions"] for row in r.rows if row["ok"]])
    print(f"revolutions per case: median {np.median(revs):.0f}, mean {revs.mean():.1f}, max {revs.max():.0f}")
    for name, m in (("paper", cf.presets.paper()), ("paper_damped", cf.presets.paper_damped())):
        c = shooting_vs_transient(m)
        print(
            f"{name} (spectral radius {c['spectral_radius']:.3g}): shooting {c['shooting_s'] * 1e3:.1f} ms "
            f"({c['shooting_revolutions']:.0f} revolutions); transient route to the orbit:"
        )
        for acc, (revs, t) in c["transient"].items():
            if revs is None:
                print(f"  {acc:.0e}: not held over the last 50 of 1000 revolutions")
            else:
                print(
                    f"  {acc:.0e}: {revs} revolutions, {t * 1e3:.1f} ms: transient / shooting = {t / c['shooting_s']:.2f}"
                )


if __name__ == "__main__":
    main()
