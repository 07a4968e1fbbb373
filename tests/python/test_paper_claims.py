# SPDX-License-Identifier: BSD-3-Clause
"""The paper's qualitative claims (section 2), checked on this model at 750 rpm, per formulation.

The study (camfollower.study) runs the paper's offset follower and an in-line one, healthy, with an
eccentric cam and with guide clearance, in the paper's literal formulation and the physical one, each
from its periodic steady state. Where the model disagrees with the paper the test asserts what the
model does and says why (docs/study.md), rather than loosening a check until it passes.
"""

import math

import numpy as np
import pytest
from camfollower import analysis as an
from camfollower.study import StudyConfig, defect_modulation, deviation_figures, run_case, run_cases

CFG = StudyConfig()


@pytest.fixture(scope="module")
def cases():
    return run_cases(CFG)


def carrier_of(case):
    return an.find_peaks(case.shaft_spectrum, 1, lo=50.0)[0][0]


def modulation(case, healthy):
    carrier = carrier_of(healthy)
    lines = lambda c: an.sidebands(c.shaft_spectrum, carrier, 12.5, orders=3)["levels"]  # noqa: E731
    return defect_modulation(lines(case), lines(healthy))


def test_response_is_periodic_at_the_cam_period_once_settled(cases):
    for key in ("offset/paper/healthy", "offset/physical/healthy"):
        h = cases[key]
        assert h.period == pytest.approx(0.08, rel=1e-12)
        assert h.settle["settled"] and h.settle["change"] <= CFG.settle_tolerance, key
        # A periodic signal's spectrum holds shaft harmonics only (rectangular window, whole revolutions).
        s = an.spectrum(h.shaft_acc, CFG.steps_per_revolution / h.period, window="rect")
        off_harmonic = np.abs(np.mod(s.frequency + 1e-9, 12.5)) > 1e-6
        assert np.max(s.amplitude[off_harmonic]) < 1e-3 * np.max(s.amplitude), key
    # The paper's dampers leave the response ringing ~4x longer than 3 % damping.
    assert (
        cases["offset/paper/healthy"].settle["revolutions"] > 3 * cases["offset/physical/healthy"].settle["revolutions"]
    )


def test_dynamic_acceleration_oscillates_about_the_theoretical_one(cases):
    for key in ("offset/paper/healthy", "offset/physical/healthy"):
        h = cases[key]
        dev = h.follower_acc - h.theory_acc
        rise = (np.mod(h.theta, 2 * np.pi) > np.radians(30)) & (np.mod(h.theta, 2 * np.pi) < np.pi)
        assert abs(np.mean(dev[rise])) < 0.1 * np.sqrt(np.mean(dev[rise] ** 2)), key
        assert 0.3 < np.sqrt(np.mean(dev[rise] ** 2)) < 10.0, key


def test_rise_versus_return_depends_on_what_the_paper_does_not_give(cases):
    """Paper: larger fluctuations on the rise than on the return. This model, with the paper's
    parameters: the opposite (the return runs at larger |pressure angle|, 23 vs 15 deg, which lowers
    the follower-train mode). With a 5 kg camshaft (the paper gives none) the order flips."""
    for key in ("offset/paper/healthy", "offset/physical/healthy"):
        d = deviation_figures(cases[key])
        assert d["return_rms"] > d["rise_rms"], key
    from camfollower.study import parameters

    heavy = run_case(
        StudyConfig(analysed_revolutions=2),
        "offset",
        "physical",
        "healthy",
        parameters(CFG, "offset", camshaft_mass=5.0),
    )
    d = deviation_figures(heavy)
    assert d["rise_rms"] > 1.05 * d["return_rms"]


def test_bearing_acceleration_spectrum_peaks_at_the_first_mode(cases):
    h = cases["offset/paper/healthy"]
    f01 = [h.model.modal_analysis(math.radians(t))["frequencies_hz"][0] for t in range(0, 360, 10)]
    peak_f = carrier_of(h)
    assert min(f01) - 12.5 <= peak_f <= max(f01) + 12.5
    # No distinct line at 2/5 f01 (the paper's parametric peak): the band around it stays far below.
    f = 0.4 * h.model.modal_analysis(0.0)["frequencies_hz"][0]
    assert h.shaft_spectrum.band(f - 30, f + 30).amplitude.max() < 0.05 * h.shaft_spectrum.amplitude.max()


def test_an_eccentric_cam_is_followed_quasi_statically(cases):
    """Physical formulation: the displaced centre moves the contact by the projection of the 10 um
    offset on the normal, eps sin(theta - alpha), and the follower (868 Hz first mode, 12.5 Hz run-out)
    simply rides it: its displacement shifts by that over cos(alpha)."""
    h, e = cases["offset/physical/healthy"], cases["offset/physical/eccentricity"]
    alpha = h.pressure_angle
    expected = CFG.eccentricity * np.sin(h.theta - alpha) / np.cos(alpha)
    assert np.max(np.abs((e.follower_disp - h.follower_disp) - expected)) < 0.05 * CFG.eccentricity
    # So it barely modulates the bearing acceleration, and changes the dwell vibration by < 2 %.
    assert modulation(e, h) < 0.05
    assert deviation_figures(e)["dwell_peak"] == pytest.approx(deviation_figures(h)["dwell_peak"], rel=0.02)
    # The settled eccentric case changes from revolution to revolution like the healthy one.
    assert e.settle["change"] <= 2 * h.settle["change"] + CFG.settle_tolerance / 10


def test_the_papers_literal_eccentricity_force_opens_the_contact(cases):
    """Paper-literal eq 6: a force K_h eps = 1900 N on camshaft and roller, ten times the ~188 N the
    return spring holds the follower with: the follower leaves the cam every revolution and the
    response is chaotic. An artefact of the formulation, flagged by a warning."""
    e = cases["offset/paper/eccentricity"]
    assert e.model.warnings and "exceeds the static contact force" in e.model.warnings[0]
    assert e.contact_loss_time > 0.01
    assert not e.settle["settled"]


def test_guide_clearance_only_matters_where_the_lateral_load_reverses(cases):
    """Offset follower: the pressure angle stays negative (-23 to -3 deg), the lateral load never
    reverses, the rod stays on one wall: the clearance changes nothing. In-line follower: the load
    reverses at the start of the rise and of the return, the rod crosses the gap and rattles."""
    off, off_h = cases["offset/physical/clearance"], cases["offset/physical/healthy"]
    assert off.clearance["impacts_per_revolution"] == 0 and off.clearance["free_flight_time_per_revolution_s"] == 0
    assert np.max(np.abs(off.follower_acc - off_h.follower_acc)) < 0.01 * np.max(np.abs(off_h.follower_acc))
    inl, inl_h = cases["inline/physical/clearance"], cases["inline/physical/healthy"]
    assert inl.clearance["wall_changes_per_revolution"] >= 1.0
    assert inl.clearance["impacts_per_revolution"] > 10
    # Rise and return vibration several times the healthy one.
    assert deviation_figures(inl)["rise_rms"] > 3 * deviation_figures(inl_h)["rise_rms"]


def test_the_imposed_side_switch_makes_the_papers_backlash_effect(cases):
    """Paper formulation (rod moved across the gap at the start of each rise and return, 10 deg ramp):
    on the offset follower it doubles the dwell vibration and modulates the bearing strongly, although
    nothing in the mechanism moves the rod (see the physical clearance above)."""
    b, h = cases["offset/paper/clearance"], cases["offset/paper/healthy"]
    assert deviation_figures(b)["dwell_peak"] > 1.8 * deviation_figures(h)["dwell_peak"]
    assert modulation(b, h) > 1.0
