# SPDX-License-Identifier: BSD-3-Clause
"""Error control that holds across output intervals (docs/solvers.md, "Error control across output
intervals"): under a tolerance, the run's error in contact force and follower acceleration, relative to
their peaks, stays within the documented band of the tolerance at every output interval from T/512 to
T/65536, on the paper preset, with the contact 100 times stiffer, and above the jump speed (contact
lost and made), against DOP853 at tolerance 1e-12 on the same output grid."""

import camfollower as cf
import numpy as np
import pytest

GRIDS = tuple(2**k for k in range(9, 17))  # output intervals T/512 ... T/65536
_P = cf.Parameters()
MODELS = {
    "preset": lambda: cf.presets.paper(_P),
    "contact_x100": lambda: cf.presets.paper(_P.replace(contact_stiffness=100 * _P.contact_stiffness)),
    "2000_rpm": lambda: cf.presets.paper(_P.replace(camshaft_speed_rpm=2000.0)),
}
# The documented band (docs/solvers.md): error / tolerance in force and acceleration, at most
# (measured at most 149x; 200x leaves room for another machine's rounding).
BAND = 200.0
# auto runs fox_goodwin on the preset and at 2000 rpm at tolerance 1e-5, dop853 at 1e-6 and 1e-7,
# radau on the stiff contact (each checked); radau and fox_goodwin (at every tolerance) on the other
# two. The explicit methods on the stiff contact are outside the band (docs/solvers.md).
CASES = [("auto", model) for model in MODELS] + [
    (method, model) for method in ("radau", "fox_goodwin") for model in ("preset", "2000_rpm")
]


HALVINGS = {"fox_goodwin": dict(max_halvings=12)}  # as auto gives it


def auto_takes(model, tolerance):
    if model == "contact_x100":
        return "radau"
    return "fox_goodwin" if tolerance >= 1e-5 else "dop853"


@pytest.fixture(scope="module")
def references():
    """DOP853 at tolerance 1e-12 per model and output grid: (force, follower acceleration)."""
    out = {}
    for name, build in MODELS.items():
        m = build()
        for n in GRIDS:
            r = cf.simulate(m, revolutions=1, time_step=m.period / n, method="dop853", tolerance=1e-12)
            out[name, n] = (np.asarray(r["cam.force"]), np.asarray(r["a.y4"]))
    return out


def errors(name, n, method, tolerance, references, **kw):
    m = MODELS[name]()
    r = cf.simulate(m, revolutions=1, time_step=m.period / n, method=method, tolerance=tolerance, **kw)
    if method == "auto":
        assert r.stats["method"] == auto_takes(name, tolerance)
    F, A = references[name, n]
    return (
        np.max(np.abs(r["cam.force"] - F)) / np.max(np.abs(F)) / tolerance,
        np.max(np.abs(r["a.y4"] - A)) / np.max(np.abs(A)) / tolerance,
    )


@pytest.mark.parametrize("method, model", CASES)
def test_the_error_stays_within_the_band_at_every_output_interval(method, model, references):
    worst = []
    for tolerance in (1e-5, 1e-6, 1e-7):
        for n in GRIDS:
            f, a = errors(model, n, method, tolerance, references, **HALVINGS.get(method, {}))
            worst.append((max(f, a), tolerance, n, f, a))
    worst.sort(reverse=True)
    print(method, model, worst[:3])
    ratio, tolerance, n, f, a = worst[0]
    assert ratio <= BAND, (
        f"{method} on {model} at tolerance {tolerance}, output T/{n}: force {f:.3g}x, "
        f"acceleration {a:.3g}x the tolerance"
    )


def test_fox_goodwin_under_a_tolerance_holds_its_tolerance_per_radian(references):
    """Its estimate is Numerov's phase lag per radian of the cam (docs/solvers.md): over a revolution
    the error stays near the tolerance whatever the output interval. With the per-step estimate it had
    before, the preset's error at tolerance 1e-7 was 4/14x the tolerance (force/acceleration) at output
    T/2048 and 215/608x at T/16384; with the velocity processed 1.4x and 16x; now both are below 1x
    (measured 0.48/0.62x and 0.49/0.64x). auto takes it at 1e-5 and looser."""
    coarse = errors("preset", 2048, "fox_goodwin", 1e-7, references, max_halvings=12)
    fine = errors("preset", 16384, "fox_goodwin", 1e-7, references, max_halvings=12)
    print(coarse, fine)
    assert max(coarse) < 3.0 and max(fine) < 3.0
    m = MODELS["preset"]()
    for tolerance, taken in ((1e-5, "fox_goodwin"), (1e-6, "dop853")):
        r = cf.simulate(m, revolutions=0.05, time_step=m.period / 16384, method="auto", tolerance=tolerance)
        assert r.stats["method"] == taken
