# SPDX-License-Identifier: BSD-3-Clause
"""Side-by-side cost of one revolution of the paper's 7-DOF model at 750 rpm, at equal accuracy.

    .venv/bin/python bench/compare.py [--out bench-out] [--quick]

Tools, all on the same model from the same static equilibrium over one revolution:
- camfollower: the whole run in C++ through the Python bindings (Newmark average acceleration);
- scipy.integrate.solve_ivp with Radau, BDF and LSODA on the same equations written in NumPy with an
  analytic Jacobian (camfollower.reference.NumpyCamFollower: what a user would otherwise write);
- Exudyn (PyPI exudyn) with the lumped model built from its own items and the contact in a user
  function, its implicit solver (bench/exudyn_model.py), when exudyn is installed.

Accuracy is measured against a converged reference: camfollower at T/2^20 (76 ns), itself checked
against Radau at rtol 1e-12. Errors are max |x - x_ref| / max |x_ref| over a common grid of T/4096 for
the follower displacement y4 and the contact force. Writes a table (printed and CSV), the speed ratio
of each tool to camfollower at equal or better accuracy, and a work-precision plot (PNG).
"""

from __future__ import annotations

import argparse
import csv
import math
import platform
import sys
import time
from pathlib import Path

import camfollower as cf
import numpy as np
from camfollower.reference import NumpyCamFollower
from scipy.integrate import solve_ivp

GRID = 4096  # comparison points per revolution


def timed(fn, repeat=1):
    """Best wall time of `repeat` calls, and the last result."""
    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def errors(y4, force, ref):
    return (
        float(np.max(np.abs(y4 - ref["y4"])) / np.max(np.abs(ref["y4"]))),
        float(np.max(np.abs(force - ref["force"])) / np.max(np.abs(ref["force"]))),
    )


def camfollower_run(model, steps_per_rev, beta=0.25):
    return cf.simulate(
        model, revolutions=1, time_step=model.period / steps_per_rev, decimation=steps_per_rev // GRID, beta=beta
    )


def reference(model, ref_model, quick):
    """camfollower at a very fine step, checked against Radau at rtol 1e-12."""
    n = 2**18 if quick else 2**20
    r = camfollower_run(model, n)
    out = {"t": r["t"], "y4": r["q"][:, 3].copy(), "force": r["cam.force"].copy(), "steps": n}
    t0 = time.perf_counter()
    rtol = 1e-10 if quick else 1e-12
    atol = np.concatenate([np.full(7, rtol * 1e-3), np.full(7, rtol * 1e-1)])
    sol = solve_ivp(
        ref_model.rhs,
        (0, out["t"][-1]),
        ref_model.initial(),
        method="Radau",
        rtol=rtol,
        atol=atol,
        jac=ref_model.jacobian,
        t_eval=out["t"],
    )
    radau_time = time.perf_counter() - t0
    force = np.array([ref_model.kh * max(ref_model.contact(t, z[:7])[1], 0.0) for t, z in zip(sol.t, sol.y.T)])
    e_y4, e_f = errors(sol.y[3], force, out)
    return out, {
        "radau_rtol": rtol,
        "radau_wall_s": radau_time,
        "reference_vs_radau_y4": e_y4,
        "reference_vs_radau_force": e_f,
    }


def scipy_run(ref_model, model, method, rtol, grid_t):
    # Absolute tolerances scaled to each variable's size, as a careful user sets them: the 10 mm
    # lift for displacements, 1 m/s for velocities.
    atol = np.concatenate([np.full(7, rtol * 1e-2), np.full(7, rtol)])
    sol = solve_ivp(
        ref_model.rhs,
        (0, grid_t[-1]),
        ref_model.initial(),
        method=method,
        rtol=rtol,
        atol=atol,
        jac=ref_model.jacobian,
        t_eval=grid_t,
    )
    if sol.status != 0:
        raise RuntimeError(f"{method} rtol={rtol}: {sol.message}")
    return sol


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="bench-out", help="folder for compare.csv and work_precision.png")
    ap.add_argument("--quick", action="store_true", help="fewer settings, coarser reference (smoke test)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    model = cf.presets.paper()
    ref_model = NumpyCamFollower(model)
    print(
        f"machine: {platform.processor() or platform.machine()}, {platform.python_implementation()} "
        f"{platform.python_version()}, numpy {np.__version__}",
        flush=True,
    )
    ref, ref_check = reference(model, ref_model, args.quick)
    print(
        f"reference: camfollower at T/{ref['steps']}; against Radau rtol {ref_check['radau_rtol']:g}: "
        f"y4 {ref_check['reference_vs_radau_y4']:.1e}, contact force {ref_check['reference_vs_radau_force']:.1e} "
        f"(Radau took {ref_check['radau_wall_s']:.1f} s)",
        flush=True,
    )
    grid_t = ref["t"]

    rows = []

    def add(tool, setting, wall, steps, y4, force):
        e_y4, e_f = errors(y4, force, ref)
        rows.append(
            {"tool": tool, "setting": setting, "wall_s": wall, "steps": steps, "err_y4": e_y4, "err_force": e_f}
        )
        print(
            f"  {tool:20s} {setting:14s} {wall * 1e3:10.2f} ms {steps:>9d} steps  y4 {e_y4:.2e}  force {e_f:.2e}",
            flush=True,
        )

    print("camfollower", flush=True)
    for k in [12, 14, 16] if args.quick else [12, 13, 14, 15, 16, 17]:
        n = 2**k
        wall, r = timed(lambda: camfollower_run(model, n), repeat=5)
        add("camfollower", f"dt=T/{n}", wall, r["stats"]["steps"], r["q"][:, 3], r["cam.force"])
    # Newmark with beta = 1/12 (Fox-Goodwin): same cost per step, far smaller phase error, but only
    # conditionally stable (omega_max dt < 2.45: at least ~2500 steps per revolution here).
    print("camfollower, beta = 1/12", flush=True)
    for k in [12, 14] if args.quick else [12, 13, 14]:
        n = 2**k
        wall, r = timed(lambda: camfollower_run(model, n, beta=1.0 / 12.0), repeat=5)
        add("camfollower b=1/12", f"dt=T/{n}", wall, r["stats"]["steps"], r["q"][:, 3], r["cam.force"])

    for method, rtols in [
        ("Radau", [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]),
        ("BDF", [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]),
        ("LSODA", [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]),
    ]:
        print(method, flush=True)
        for rtol in rtols[::2] if args.quick else rtols:
            wall, sol = timed(lambda: scipy_run(ref_model, model, method, rtol, grid_t))
            force = np.array([ref_model.kh * max(ref_model.contact(t, z[:7])[1], 0.0) for t, z in zip(sol.t, sol.y.T)])
            add(f"scipy {method}", f"rtol={rtol:g}", wall, int(sol.nfev), sol.y[3], force)

    try:
        sys.path.insert(0, str(Path(__file__).parent))
        from exudyn_model import run_exudyn  # noqa: E402
    except ImportError as e:
        print(f"Exudyn: skipped ({e})", flush=True)
    else:
        print("Exudyn", flush=True)
        for k in [12, 14] if args.quick else [12, 13, 14, 15, 16]:
            n = 2**k
            r = run_exudyn(model, model.period, model.period / n, record_every=max(1, n // GRID))
            y4 = np.interp(grid_t, r["t"], r["y4"])
            force = np.interp(grid_t, r["t"], r["cam.force"])
            add("Exudyn", f"dt=T/{n}", r["wall_time_s"], r["steps"], y4, force)

    with open(out / "compare.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    # Speed ratio at equal or better accuracy: for each tool, its fastest run reaching the target,
    # against the fastest camfollower run (default scheme, then beta = 1/12) reaching the same target.
    tools = list(dict.fromkeys(r["tool"] for r in rows))
    targets = [1e-4, 1e-5, 1e-6]

    def fastest(name, target):
        ok = [r for r in rows if r["tool"] == name and r["err_y4"] <= target]
        return min(ok, key=lambda r: r["wall_s"]) if ok else None

    for base_tool in ("camfollower", "camfollower b=1/12"):
        print(
            f"\nspeed ratio tool / {base_tool} at equal or better accuracy in y4 "
            "(wall time of the fastest run reaching the target)"
        )
        print(f"  {'tool':20s}" + "".join(f"{f'<= {t:g}':>22s}" for t in targets))
        for tool in tools:
            cells = []
            for target in targets:
                mine, base = fastest(tool, target), fastest(base_tool, target)
                if mine is None or base is None:
                    cells.append("not reached")
                else:
                    cells.append(f"{mine['wall_s'] / base['wall_s']:8.1f}x ({mine['wall_s'] * 1e3:.1f} ms)")
            print(f"  {tool:20s}" + "".join(f"{c:>22s}" for c in cells))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(10, 5.5))
    for tool in tools:
        pts = [(r["wall_s"], r["err_y4"]) for r in rows if r["tool"] == tool]  # in order of the setting
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=tool)
    ax.set_xlabel("wall time for one revolution (s)")
    ax.set_ylabel("max relative error in follower displacement y4")
    ax.set_title("Work-precision: 7-DOF cam-follower, one revolution at 750 rpm")
    ax.grid(which="both", alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(out / "work_precision.png", dpi=110)
    print(f"\nwrote {out}/compare.csv and {out}/work_precision.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
