"""The paper's qualitative claims (section 2), checked on this model at 750 rpm.

Where the model disagrees with the paper, the test asserts what the model does and says why, rather
than loosening a check until it passes. See docs/study.md for the discussion.
"""

import math

import numpy as np
import pytest

from camfollower import Defects
from camfollower import analysis as an
from camfollower.study import StudyConfig, defect_modulation, run_case

CFG = StudyConfig()


@pytest.fixture(scope="module")
def cases():
    return {
        "healthy": run_case("healthy", Defects(), CFG),
        "eccentricity": run_case("eccentricity", Defects(eccentricity=10e-6), CFG),
        "backlash": run_case("backlash", Defects(backlash=10e-6, backlash_switch_width=math.radians(10)), CFG),
    }


def dwell_peak(case, signal):
    return max(s["peak"] for s in an.phase_statistics(case.model, case.theta, signal) if s["phase"].startswith("dwell"))


def sideband_lines(case, carrier):
    return an.sidebands(case.shaft_spectrum, carrier, 12.5, orders=3)["levels"]


def test_response_is_periodic_at_the_cam_period_after_the_transient(cases):
    h = cases["healthy"]
    assert h.model.period == pytest.approx(0.08, rel=1e-12)
    # Last revolution against the one before: identical to 1e-3 of the 44 m/s^2 peak.
    assert h.stats["periodicity_follower_acc"] < 1e-3 * 44.0
    # And the spectrum of a periodic signal is made of shaft harmonics only (rectangular window over
    # whole revolutions: no leakage into the bins between harmonics).
    s = an.spectrum(h.shaft_acc, CFG.steps_per_revolution / h.model.period, window="rect")
    off_harmonic = np.abs(np.mod(s.frequency + 1e-9, 12.5)) > 1e-6
    assert np.max(s.amplitude[off_harmonic]) < 1e-3 * np.max(s.amplitude)


def test_dynamic_acceleration_oscillates_about_the_theoretical_one(cases):
    h = cases["healthy"]
    dev = h.follower_acc - h.theory_acc
    stats = {s["phase"].split()[0]: s for s in an.phase_statistics(h.model, h.theta, dev)}
    # Oscillation about the rigid-body curve: zero mean, a few m/s^2 of RMS.
    rise = (np.mod(h.theta, 2 * np.pi) > np.radians(30)) & (np.mod(h.theta, 2 * np.pi) < np.pi)
    assert abs(np.mean(dev[rise])) < 0.05 * np.sqrt(np.mean(dev[rise] ** 2))
    assert 1.0 < stats["rise"]["rms"] < 10.0
    # Paper: fluctuations larger on the rise than on the return. This model: the opposite. The two
    # segments have the same law; the return runs at larger |pressure angle| (up to 23 deg against
    # 15 deg), which lowers the follower-train mode (828 Hz vs 897 Hz) and feeds more of the motion's
    # jerk into it. Documented finding, not reproduced.
    assert stats["return"]["rms"] > stats["rise"]["rms"]


def test_bearing_acceleration_spectrum_peaks_at_the_first_mode(cases):
    h = cases["healthy"]
    f01 = [h.model.modal_analysis(math.radians(t))["frequencies_hz"][0] for t in range(0, 360, 5)]
    peak_f, _ = an.find_peaks(h.shaft_spectrum, 1, lo=50.0)[0]
    # The dominant line sits inside the band the first mode sweeps as the pressure angle varies.
    assert min(f01) - 12.5 <= peak_f <= max(f01) + 12.5
    # The bearing-dominated 2747 Hz mode shows as a secondary hump, far weaker.
    f03 = h.model.modal_analysis(0.0)["frequencies_hz"][2]
    band = h.shaft_spectrum.band(f03 - 150, f03 + 150)
    assert 0 < band.amplitude.max() < 0.2 * h.shaft_spectrum.amplitude.max()


def test_eccentricity_is_followed_quasi_statically(cases):
    """Why the eccentricity barely shows: at 12.5 Hz, far below the 868 Hz first mode, the follower
    simply rides the 10 um runout. Its displacement shifts by de_c / cos(alpha)."""
    h, e = cases["healthy"], cases["eccentricity"]
    # Recompute the follower displacement over the analysed window from a fresh run of each case.
    import camfollower as cf

    n = CFG.steps_per_revolution
    ys = []
    for case in (h, e):
        r = cf.simulate(case.model, revolutions=CFG.revolutions, time_step=case.model.period / n, decimation=16)
        w = an.last_revolutions(r, case.model.period, 2)
        ys.append((r["q"][w, 3], r["theta"][w], r["pressure_angle"][w]))
    (y_h, theta, _), (y_e, _, alpha) = ys
    expected = 10e-6 * np.sin(theta) / np.cos(alpha)
    assert np.max(np.abs((y_e - y_h) - expected)) < 0.05 * 10e-6


def test_eccentricity_sidebands_around_the_peak(cases):
    """Paper: eccentricity adds +-12.5 Hz sidebands (amplitude modulation). This model: the lines at
    +-12.5 Hz change by well under 1 % of the carrier: not reproduced (see the quasi-static test)."""
    h, e = cases["healthy"], cases["eccentricity"]
    carrier = an.find_peaks(h.shaft_spectrum, 1, lo=50.0)[0][0]
    added = defect_modulation(sideband_lines(e, carrier), sideband_lines(h, carrier))
    assert 0 < added < 0.01


def test_defects_raise_follower_acceleration_and_contact_force_on_the_dwells(cases):
    h, e, b = cases["healthy"], cases["eccentricity"], cases["backlash"]
    dev = {k: dwell_peak(c, c.follower_acc - c.theory_acc) for k, c in cases.items()}
    force = {k: dwell_peak(c, c.contact_force) for k, c in cases.items()}
    # Backlash: clearly (more than doubles the dwell vibration, adds > 5 N to the dwell force peak).
    assert dev["backlash"] > 2 * dev["healthy"]
    assert force["backlash"] > force["healthy"] + 5
    # Eccentricity: raised, but only just (< 1 % and < 0.5 N): the paper's large increase is not reproduced.
    assert dev["healthy"] < dev["eccentricity"] < 1.01 * dev["healthy"]
    assert force["healthy"] < force["eccentricity"] < force["healthy"] + 0.5


def test_which_defect_modulates_the_bearing_acceleration_more(cases):
    """Paper: eccentricity modulates the bearing acceleration more than backlash. This model: the
    reverse, by two orders of magnitude (backlash drives the guide with K_rb x 20 um at each switch)."""
    h = cases["healthy"]
    carrier = an.find_peaks(h.shaft_spectrum, 1, lo=50.0)[0][0]
    ecc = defect_modulation(sideband_lines(cases["eccentricity"], carrier), sideband_lines(h, carrier))
    back = defect_modulation(sideband_lines(cases["backlash"], carrier), sideband_lines(h, carrier))
    assert back > 100 * ecc
