# SPDX-License-Identifier: BSD-3-Clause
"""Cost per step against the number of cams, from camfollower_bench_camshaft's JSON output:

    build-bench/bench/camfollower_bench_camshaft --benchmark_out=camshaft.json --benchmark_out_format=json
    .venv/bin/python bench/camshaft_scaling.py camshaft.json

Prints, per backend, microseconds per step and DOFs for each cam count, the exponent p of a least-squares
fit cost ~ N^p (over N >= 4, where the shaft dominates the fixed costs), the dense/sparse cost ratio per N and
the crossover (the smallest N from which the sparse backend is faster).
"""

import json
import math
import sys


def main(path):
    runs = json.load(open(path))["benchmarks"]
    cost = {}  # (backend, cams) -> us per step
    dofs = {}
    for b in runs:
        if not b["name"].startswith("BM_CamshaftSteps/") or b.get("run_type") == "aggregate":
            continue
        _, cams, backend = b["name"].split("/")[:3]
        key = ("dense" if backend == "0" else "sparse", int(cams))
        cost[key] = 1e6 / b["items_per_second"]
        dofs[int(cams)] = int(b["dofs"])
    for backend in ("dense", "sparse"):
        ns = sorted(n for (k, n) in cost if k == backend)
        print(f"{backend}: " + ", ".join(f"N={n}: {cost[(backend, n)]:.1f} us ({dofs[n]} DOFs)" for n in ns))
        fit = [(math.log(n), math.log(cost[(backend, n)])) for n in ns if n >= 4]
        if len(fit) >= 2:
            mx = sum(x for x, _ in fit) / len(fit)
            my = sum(y for _, y in fit) / len(fit)
            slope = sum((x - mx) * (y - my) for x, y in fit) / sum((x - mx) ** 2 for x, _ in fit)
            print(f"  cost per step ~ N^{slope:.2f} (N >= 4)")
    common = sorted(n for (k, n) in cost if k == "dense" and ("sparse", n) in cost)
    print("dense / sparse cost: " + ", ".join(f"N={n}: {cost[('dense', n)] / cost[('sparse', n)]:.2f}" for n in common))
    faster = [n for n in common if cost[("sparse", n)] < cost[("dense", n)]]
    crossover = next((n for n in common if all(m in faster for m in common if m >= n)), None)
    print(
        f"crossover: sparse faster from N = {crossover} cams ({dofs.get(crossover, '?')} DOFs) on"
        if crossover
        else "crossover: none in this range"
    )


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench-out/camshaft.json")
