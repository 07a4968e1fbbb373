# SPDX-License-Identifier: BSD-3-Clause
"""Step-size convergence of the 16-cam valve train (an inline-8 intake camshaft, or both camshafts of an
inline-4 DOHC head) at 6000 engine rpm: one camshaft revolution from the quasi-static start at several
time steps, each compared with the run at the smallest step on a common 20 us grid.

    .venv/bin/python bench/valve_train_accuracy.py

Prints per time step the largest contact-force and valve-displacement differences (relative to the
largest value), Newton iterations per step and the wall time of the run (context only: the cost is
measured by build-bench/bench/camfollower_bench_camshaft, BM_ValveTrainRevolution).
"""

import time

import camfollower as cf
import numpy as np


def main():
    m = cf.presets.valve_train(engine_speed_rpm=6000, cylinders=8, firing_order=[1, 8, 7, 3, 6, 5, 4, 2])
    grid = 20e-6
    steps = [1.25e-6, 2.5e-6, 5e-6, 10e-6, 20e-6]
    runs = {}
    for dt in steps:
        start = time.perf_counter()
        r = cf.simulate(m, revolutions=1, time_step=dt, decimation=int(round(grid / dt)))
        runs[dt] = (r, time.perf_counter() - start)
    ref = runs[steps[0]][0]
    names = m.contact_names
    dofs = m.follower_dofs
    fmax = max(np.abs(np.asarray(ref[f"{n}.force"])).max() for n in names)
    qmax = max(np.abs(np.asarray(ref[f"q.{d}"])).max() for d in dofs)
    print(f"{m.size} DOFs, {len(names)} cams, camshaft {m.camshaft_speed_rpm:g} rpm, backend {ref.stats['backend']}")
    print("time step   force error   valve error   Newton/step   wall time")
    for dt in steps[1:]:
        r, wall = runs[dt]
        n = min(r.rows, ref.rows)
        df = max(np.abs(np.asarray(r[f"{c}.force"])[:n] - np.asarray(ref[f"{c}.force"])[:n]).max() for c in names)
        dq = max(np.abs(np.asarray(r[f"q.{d}"])[:n] - np.asarray(ref[f"q.{d}"])[:n]).max() for d in dofs)
        print(
            f"{dt * 1e6:6.2f} us   {df / fmax:11.2e}   {dq / qmax:11.2e}   {r.stats['mean_iterations']:11.2f}   {wall:7.3f} s"
        )


if __name__ == "__main__":
    main()
