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
# auto runs dop853 on the preset and at 2000 rpm, radau on the stiff contact (each checked); radau
# on the other two. The explicit methods on the stiff contact are outside the band (docs/solvers.md).
CASES = [("auto", model) for model in MODELS] + [("radau", "preset"), ("radau", "2000_rpm")]
AUTO_TAKES = {"preset": "dop853", "contact_x100": "radau", "2000_rpm": "dop853"}


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
        assert r.stats["method"] == AUTO_TAKES[name]
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
            f, a = errors(model, n, method, tolerance, references)
            worst.append((max(f, a), tolerance, n, f, a))
    worst.sort(reverse=True)
    print(method, model, worst[:3])
    ratio, tolerance, n, f, a = worst[0]
    assert ratio <= BAND, (
        f"{method} on {model} at tolerance {tolerance}, output T/{n}: force {f:.3g}x, "
        f"acceleration {a:.3g}x the tolerance"
    )


def test_fox_goodwin_under_a_tolerance_holds_the_band_since_its_velocity_is_processed(references):
    """Its error per step is controlled; with the trapezoidal velocity the run's error was not held (on
    the preset at 1e-7: 4/14x the tolerance at output T/2048, 215/608x at T/16384). With the velocity
    processed to fourth order both are within the band (measured 1.4x and 16x; docs/solvers.md). auto
    still takes DOP853 there (its rule predates this)."""
    coarse = errors("preset", 2048, "fox_goodwin", 1e-7, references, max_halvings=12)
    fine = errors("preset", 16384, "fox_goodwin", 1e-7, references, max_halvings=12)
    print(coarse, fine)
    assert max(coarse) < 30.0 and max(fine) < BAND
    m = MODELS["preset"]()
    assert (
        cf.simulate(m, revolutions=0.05, time_step=m.period / 16384, method="auto", tolerance=1e-7).stats["method"]
        == "dop853"
    )
