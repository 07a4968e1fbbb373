# SPDX-License-Identifier: BSD-3-Clause
"""How the cost of a camfollower run scales with simulated duration and with the time step.

    .venv/bin/python bench/scaling.py

Each case runs in a fresh Python process (so its peak resident memory is its own): wall time of
cf.simulate and peak RSS for 1, 10 and 100 revolutions, with every step recorded and with output
decimated by 1000; then wall time against the step size for one revolution.
"""

from __future__ import annotations

import json
import subprocess
import sys

CASE = """
import json, resource, time
import camfollower as cf
m = cf.presets.paper()
t0 = time.perf_counter()
r = cf.simulate(m, revolutions={revs}, time_step=m.period / {n}, decimation={dec})
wall = time.perf_counter() - t0
print(json.dumps({{"wall_s": wall, "steps": r["stats"]["steps"], "rows": int(r["t"].size),
                  "peak_rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}}))
"""


def run(revs: int, n: int, dec: int) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", CASE.format(revs=revs, n=n, dec=dec)], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out)


def main() -> int:
    n = 32768
    print(f"duration scaling at dt = T/{n} (one revolution = {n} steps)")
    print(
        f"{'revolutions':>11s} {'decimation':>10s} {'wall (s)':>9s} {'us/step':>8s} {'rows':>9s} {'peak RSS (MiB)':>15s}"
    )
    base = None
    for dec in (1, 1000):
        for revs in (1, 10, 100):
            r = run(revs, n, dec)
            per_step = 1e6 * r["wall_s"] / r["steps"]
            base = base or r["peak_rss_mib"]
            print(f"{revs:11d} {dec:10d} {r['wall_s']:9.3f} {per_step:8.3f} {r['rows']:9d} {r['peak_rss_mib']:15.1f}")
    print("\nstep-size scaling, one revolution, decimation 1000")
    print(f"{'steps/rev':>9s} {'wall (ms)':>10s} {'us/step':>8s}")
    for k in range(12, 19, 2):
        r = run(1, 2**k, 1000)
        print(f"{2**k:9d} {1e3 * r['wall_s']:10.2f} {1e6 * r['wall_s'] / r['steps']:8.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
