# SPDX-License-Identifier: BSD-3-Clause
"""What `auto` under a tolerance costs against Fox-Goodwin under the same tolerance, side by side in one
process: one revolution at output T/2048 on the paper preset and with the contact 100 times stiffer;
CPU ms medians of interleaved runs, force error against DOP853 at 1e-12 (docs/benchmarks.md). Where
`auto` takes Fox-Goodwin itself (ringing modes, tolerance 1e-5 and looser) the ratio measures only
the choice's own cost; below 1e-5 and on the stiffer contact it compares the method `auto` takes
(DOP853, Radau) with Fox-Goodwin. Run: .venv/bin/python bench/auto_cost.py"""

import time

import camfollower as cf
import numpy as np

REPEATS = 7


def main():
    p = cf.Parameters()
    models = {
        "750 rpm": cf.presets.paper(p),
        "x100 contact": cf.presets.paper(p.replace(contact_stiffness=100 * p.contact_stiffness)),
    }
    runs = {"auto": dict(method="auto"), "fox_goodwin": dict(method="fox_goodwin", max_halvings=12)}
    print("case, tolerance, then per run: method, CPU ms, force error; ratio auto / fox_goodwin")
    for name, m in models.items():
        grid = dict(revolutions=1, time_step=m.period / 2048)
        ref = np.asarray(cf.simulate(m, **grid, method="dop853", tolerance=1e-12)["cam.force"])
        for tolerance in (1e-4, 1e-6, 1e-7):
            times = {k: [] for k in runs}
            last = {}
            for _ in range(REPEATS):
                for k, kw in runs.items():
                    start = time.process_time()
                    last[k] = cf.simulate(m, **grid, tolerance=tolerance, **kw)
                    times[k].append(time.process_time() - start)
            cells = []
            for k, r in last.items():
                error = np.max(np.abs(np.asarray(r["cam.force"]) - ref)) / np.max(np.abs(ref))
                cells.append(f"{r.stats['method']} {1e3 * np.median(times[k]):.2f} ms {error:.1e}")
            ratio = np.median(times["auto"]) / np.median(times["fox_goodwin"])
            print(f"{name}, {tolerance:.0e}: " + " | ".join(cells) + f"; ratio {ratio:.2f}")


if __name__ == "__main__":
    main()
