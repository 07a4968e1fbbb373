# SPDX-License-Identifier: BSD-3-Clause
"""Step-size convergence of the 16-cam valve train (an inline-8 intake camshaft, or both camshafts of an
inline-4 DOHC head) at 6000 engine rpm: one camshaft revolution from the quasi-static start with
average-acceleration Newmark and with Fox-Goodwin (on the sparse backend with its trapezoidal
velocity, docs/solvers.md) at several time steps, each compared on a common 20 us grid with Newmark
at 0.078 us (itself checked against Fox-Goodwin at 0.156 us).

    .venv/bin/python bench/valve_train_accuracy.py

Prints per run the largest contact-force and valve-displacement differences (relative to the largest
value), Newton iterations per step and the wall time of the run (context only: the cost is measured
by build-bench/bench/camfollower_bench_camshaft, BM_ValveTrainRevolution).
"""

import time

import camfollower as cf
import numpy as np

GRID = 20e-6  # s, the common output grid


def main():
    m = cf.presets.valve_train(engine_speed_rpm=6000, cylinders=8, firing_order=[1, 8, 7, 3, 6, 5, 4, 2])
    names, dofs = m.contact_names, m.follower_dofs

    def run(method, dt):
        start = time.perf_counter()
        r = cf.simulate(m, revolutions=1, method=method, time_step=dt, decimation=int(round(GRID / dt)))
        return r, time.perf_counter() - start

    ref, _ = run("newmark", 0.078125e-6)
    fmax = max(np.abs(np.asarray(ref[f"{n}.force"])).max() for n in names)
    qmax = max(np.abs(np.asarray(ref[f"q.{d}"])).max() for d in dofs)

    def errors(r):
        n = min(r.rows, ref.rows)
        df = max(np.abs(np.asarray(r[f"{c}.force"])[:n] - np.asarray(ref[f"{c}.force"])[:n]).max() for c in names)
        dq = max(np.abs(np.asarray(r[f"q.{d}"])[:n] - np.asarray(ref[f"q.{d}"])[:n]).max() for d in dofs)
        return df / fmax, dq / qmax

    print(f"{m.size} DOFs, {len(names)} cams, camshaft {m.camshaft_speed_rpm:g} rpm, backend {ref.stats['backend']}")
    check, _ = run("fox_goodwin", 0.15625e-6)
    print(f"reference: newmark 0.078 us; fox_goodwin 0.156 us differs by {errors(check)[0]:.2e} in force")
    print("method        time step   force error   valve error   Newton/step   wall time")
    for method, steps in (
        ("newmark", [0.3125e-6, 0.625e-6, 1.25e-6, 2.5e-6, 5e-6, 10e-6]),
        ("fox_goodwin", [0.3125e-6, 0.625e-6, 1.0e-6]),
    ):
        for dt in steps:
            r, wall = run(method, dt)
            df, dq = errors(r)
            print(
                f"{method:12s} {dt * 1e6:7.4f} us   {df:11.2e}   {dq:11.2e}   {r.stats['mean_iterations']:11.2f}"
                f"   {wall:7.3f} s"
            )


if __name__ == "__main__":
    main()
