# SPDX-License-Identifier: BSD-3-Clause
"""Lift synthesis benchmark (docs/synthesis.md, "What it achieves"): the synthesized lift against the
catalogue laws and the polydyne baseline, on the paper preset and the indexing-cam example.

For each case, every design is simulated afresh by ``synthesis.verify`` (a periodic steady state at
accuracy 1e-4 per speed, nothing reused from the optimizer) at the design speed and over +/-20 % of it:
the output's residual vibration in the dwells (largest peak-to-peak less the quasi-static path), its
peak acceleration, the smallest contact force. The synthesis is limited to 1.1 times the peak
acceleration of the catalogue law with the least residual at the design speed, both the rigid
follower's (a kinematic limit) and the output's in the flexible response.

    .venv/bin/python bench/synthesis.py [--case paper|indexing|all] [-o DIR]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path

import camfollower as cf
import numpy as np
from camfollower import synthesis

ROOT = Path(__file__).resolve().parent.parent
BAND = (0.8, 0.9, 1.0, 1.1, 1.2)


def paper_case():
    system = cf.presets.paper()
    p = cf.Parameters()
    # One-mass equivalent for the polydyne baseline: the follower mass on the series stiffness of the
    # chain from the shaft to it (bearing, Hertz contact linearized, roller pin, rod), with the mass
    # chosen so that it rings at the mechanism's lowest natural frequency.
    chain = 1.0 / sum(
        1.0 / k
        for k in (p.bearing_stiffness_vertical, p.contact_stiffness, p.roller_pin_stiffness_vertical, p.rod_stiffness)
    )
    f1 = float(np.min(system.modal_analysis(0.0)["frequencies_hz"]))
    one_mass = {"mass": chain / (2 * math.pi * f1) ** 2, "stiffness": chain, "return_stiffness": p.spring_stiffness}
    return "paper", system, "y4", one_mass


def indexing_case():
    system = cf.load_config(ROOT / "examples" / "indexing_cam.toml").mechanism
    # The slide (4 kg) on the push rod (2e6 N/m, 60 N s/m), held by the 6 N/mm return spring: exactly
    # polydyne's one-mass model with the carrier rigid on the cam.
    one_mass = {"mass": 4.0, "stiffness": 2e6, "return_stiffness": 6e3, "damping": 60.0}
    return "indexing", system, "slide", one_mass


def c4_wanted(program):
    """The C4 motion polydyne is asked to produce: each rise and return as the degree-9 polynomial with
    zero derivatives through the fourth at its ends."""
    segments = []
    for s in program.segments:
        if s.h_end == s.h_start:
            segments.append(s)
        else:
            segments.append(
                cf.Segment.polynomial(s.theta_start, s.theta_end, [s.h_start, 0, 0, 0, 0], [s.h_end, 0, 0, 0, 0])
            )
    return cf.MotionProgram(segments)


def row_text(name, rows, design_index):
    cells = " ".join(f"{r['residual']:10.3e}" for r in rows)
    d = rows[design_index]
    return f"{name:24s} {cells}  {d['max_abs_acceleration']:8.2f} {d['rigid_max_abs_acceleration']:8.2f} {min(r['min_force_N'] for r in rows):8.1f}"


def run_case(make, out: Path, workers: int):
    name, system, output, one_mass = make()
    contact = system.contact_names[0]
    program = next(c["program"] for c in system.builder().contacts if c["name"] == contact)
    design = float(system.camshaft_speed_rpm)
    speeds = [design * f for f in BAND]
    di = BAND.index(1.0)
    designs, results = {}, {}
    for law in synthesis.CATALOGUE:
        designs[law] = synthesis.with_laws(program, law)
    rows = {k: synthesis.verify(system, v, speeds, output=output) for k, v in designs.items()}
    best = min(synthesis.CATALOGUE, key=lambda k: rows[k][di]["residual"])
    limit = 1.1 * rows[best][di]["rigid_max_abs_acceleration"]
    output_limit = 1.1 * rows[best][di]["max_abs_acceleration"]
    wanted = c4_wanted(program)
    designs["polydyne"] = synthesis.polydyne(wanted, speed_rpm=design, **one_mass)
    rows["polydyne"] = synthesis.verify(system, designs["polydyne"], speeds, output=output)
    start = designs[best]
    # One speed: the default 8 stations per segment; the band: 16 (a lift that stays quiet over +/-20 %
    # needs a finer shape; measured: 12 stations leave the indexing cam's band at ~1e-6 m, 16 at ~5e-9 m).
    for label, band, nodes in (("synthesis (design speed)", 0.0, 8), ("synthesis (+/-20 % band)", 0.2, 16)):
        t0 = time.perf_counter()
        r = synthesis.synthesize(
            system,
            output=output,
            start=start,
            band=band,
            nodes=nodes,
            max_acceleration=limit,
            max_output_acceleration=output_limit,
            workers=workers,
            max_evaluations=1000,
        )
        results[label] = r
        designs[label] = r.program
        rows[label] = synthesis.verify(system, r.program, speeds, output=output)
        print(
            f"  {label}: {r.evaluations} steady states, {r.revolutions:.0f} revolutions, {time.perf_counter() - t0:.1f} s wall, "
            f"converged {r.converged} ({r.message})",
            flush=True,
        )
    header = " ".join(f"{s:8.0f}rpm" for s in speeds)
    print(
        f"\n{name}: residual vibration of {output} (peak-to-peak in the dwells) / peak |a| at {design:g} rpm "
        f"(flexible, rigid) / least contact force over the band"
    )
    print(f"{'design':24s} {header}  {'a_flex':>8s} {'a_rigid':>8s} {'F_min N':>8s}")
    for k in rows:
        print(row_text(k, rows[k], di))
    best_at = [min(rows[k][i]["residual"] for k in synthesis.CATALOGUE) for i in range(len(speeds))]
    summary = {
        "case": name,
        "output": output,
        "speeds_rpm": speeds,
        "best_catalogue_law": best,
        "acceleration_limit": limit,
        "rows": rows,
        "best_catalogue_residual": best_at,
        "targets": {},
    }
    for label, r in results.items():
        ratios = [b / max(x["residual"], 1e-300) for b, x in zip(best_at, rows[label])]
        summary["targets"][label] = {
            "design_ratio": ratios[di],
            "band_worst_ratio": min(ratios),
            "band_ratio_of_worst": max(best_at) / max(x["residual"] for x in rows[label]),
            "peak_acceleration_vs_best_law": rows[label][di]["max_abs_acceleration"]
            / rows[best][di]["max_abs_acceleration"],
            "rigid_peak_acceleration_vs_best_law": rows[label][di]["rigid_max_abs_acceleration"]
            / rows[best][di]["rigid_max_abs_acceleration"],
            "beats_polydyne_off_design": all(
                x["residual"] < p["residual"] for j, (x, p) in enumerate(zip(rows[label], rows["polydyne"])) if j != di
            ),
            "evaluations": r.evaluations,
            "wall_time_s": r.wall_time,
            "optimizer_final": r.objective_final,
            "kinematics": r.kinematics["final"],
        }
        t = summary["targets"][label]
        print(
            f"  {label}: residual vs best catalogue law {t['design_ratio']:.1f}x lower at the design speed, "
            f">= {t['band_worst_ratio']:.1f}x at every band speed, worst over the band {t['band_ratio_of_worst']:.1f}x; "
            f"peak |a| {100 * (t['peak_acceleration_vs_best_law'] - 1):+.1f} % vs {best} (rigid "
            f"{100 * (t['rigid_peak_acceleration_vs_best_law'] - 1):+.1f} %); beats polydyne off design: "
            f"{t['beats_polydyne_off_design']}; {t['evaluations']} steady states, {t['wall_time_s']:.1f} s"
        )
    out.mkdir(parents=True, exist_ok=True)
    (out / f"synthesis_{name}.json").write_text(json.dumps(summary, indent=1, default=float))
    _figure(out / f"synthesis_{name}.png", name, output, speeds, rows, designs, design)
    return summary


def _figure(path, name, output, speeds, rows, designs, design):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.5))
    theta = np.linspace(0, 2 * math.pi, 2000)
    omega = design * math.pi / 30
    for k in rows:
        style = "-" if k.startswith("synthesis") else ("--" if k == "polydyne" else ":")
        ax.semilogy(speeds, [r["residual"] * 1e6 for r in rows[k]], style, marker="o", label=k)
        bx.plot(np.degrees(theta), np.asarray(designs[k].evaluate(theta)["d2h"]) * omega**2, style, label=k)
    ax.set_xlabel("camshaft speed (rpm)")
    ax.set_ylabel(f"residual vibration of {output} (um, peak-to-peak)")
    ax.set_title(f"{name}: residual vibration in the dwells")
    ax.grid(True, which="both", alpha=0.3)
    bx.set_xlabel("cam angle (deg)")
    bx.set_ylabel(f"rigid follower acceleration at {design:g} rpm (m/s^2)")
    bx.set_title("cam acceleration")
    bx.set_xlim(0, 360)
    bx.set_xticks(range(0, 361, 45))
    bx.grid(True, alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=9)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", choices=["paper", "indexing", "all"], default="all")
    parser.add_argument("-o", "--output", default="synthesis-bench")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()
    cases = {"paper": paper_case, "indexing": indexing_case}
    for key, make in cases.items():
        if args.case in (key, "all"):
            print(f"case {key}:", flush=True)
            run_case(make, Path(args.output), args.workers)


if __name__ == "__main__":
    main()
