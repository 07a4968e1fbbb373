# SPDX-License-Identifier: BSD-3-Clause
"""Redraw latency of the design page (docs/design.md, "How fast it redraws"): headless Chromium edits a
field and waits until all four figures (SVAJ, profile, response, geometry) are drawn again.

Per edit: ``latency`` from the key press to the last figure drawn (the browser's clock: the request,
the library's work, the JSON, Plotly's drawing), and the server's share (``server``: build, kinematics,
the quick periodic steady state, the figures). Edits alternate between a segment's lift and the
camshaft speed, so every one changes the design. The background work (refining, the margin curve) is
cancelled after each edit, as a user's next edit would, so that it does not share the cores with the
next measurement; ``--with-background`` leaves it running (the page as a user has it).

    .venv/bin/python bench/design_latency.py [--edits 20] [--case paper|roller|all] [--with-background]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
from pathlib import Path

from camfollower.design import testing as T

ROOT = Path(__file__).resolve().parent.parent
CASES = {
    # (config or None for the paper's mechanism, lift field, two lifts, two speeds)
    "paper": (None, "program.paper.segments[1].h", ("9.5 mm", "10 mm"), ("740", "750")),
    "roller": (
        str(ROOT / "examples" / "translating_roller.toml"),
        "program.feed.segments[1].h",
        ("11.5 mm", "12 mm"),
        ("590", "600"),
    ),
}


def measure(name: str, edits: int, background: bool, folder: Path) -> dict:
    config, lift, lifts, speeds = CASES[name]
    browser = T.chromium()
    try:
        with T.running_page(config, root=str(folder)) as (page, url):
            T.open_page(browser, url)
            rows = []
            for i in range(edits + 2):  # the first two warm up (the browser's JIT, the warm start)
                path, values = (lift, lifts) if i % 2 == 0 else ("camshaft.speed", speeds)
                r = T.edit(browser, path, values[(i // 2) % 2])
                r["path"] = path
                if not background:
                    T.element(browser, "cancel").click()
                    T.wait(page.jobs.idle, 60, "the cancelled step's end")
                if i >= 2:
                    rows.append(r)
    finally:
        browser.quit()
    latency = sorted(r["latency_ms"] for r in rows)
    lift_edits = [r["latency_ms"] for r in rows if r["path"] != "camshaft.speed"]
    speed_edits = [r["latency_ms"] for r in rows if r["path"] == "camshaft.speed"]
    server = sorted(r["total_ms"] for r in rows)
    response = sorted(r["response_ms"] for r in rows)
    pick = lambda xs, q: xs[min(len(xs) - 1, int(round(q * (len(xs) - 1))))]
    return {
        "case": name,
        "edits": len(rows),
        "latency_median_ms": statistics.median(latency),
        "latency_p90_ms": pick(latency, 0.9),
        "latency_max_ms": latency[-1],
        "lift_median_ms": statistics.median(lift_edits),
        "speed_median_ms": statistics.median(speed_edits),
        "server_median_ms": statistics.median(server),
        "steady_state_median_ms": statistics.median(response),
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=20)
    parser.add_argument("--case", choices=("paper", "roller", "all"), default="all")
    parser.add_argument("--with-background", action="store_true")
    args = parser.parse_args(argv)
    why = T.browser_missing()
    if why:
        print(f"design_latency: {why}", file=sys.stderr)
        return 1
    print(f"load average {os.getloadavg()[0]:.2f} (2 cores: above ~0.5 the figures are noisy)")
    folder = Path(os.environ.get("TMPDIR", "/tmp")) / "camfollower-design-bench"
    folder.mkdir(exist_ok=True)
    print(
        "| case | edits | latency median (ms) | p90 | max | lift edits (4 figures) median | speed edits "
        "(2 figures) median | server median (ms) | of it the steady state (ms) |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for name in CASES if args.case == "all" else (args.case,):
        r = measure(name, args.edits, args.with_background, folder)
        print(
            f"| {name} | {r['edits']} | {r['latency_median_ms']:.0f} | {r['latency_p90_ms']:.0f} | "
            f"{r['latency_max_ms']:.0f} | {r['lift_median_ms']:.0f} | {r['speed_median_ms']:.0f} | "
            f"{r['server_median_ms']:.0f} | {r['steady_state_median_ms']:.0f} |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
