# SPDX-License-Identifier: BSD-3-Clause
"""Analysis helpers on signals with known answers."""

import math

import camfollower as cf
import numpy as np
import pytest
from camfollower import analysis as an


def test_spectrum_reads_the_amplitude_of_a_sinusoid_on_a_bin():
    fs, n = 10000.0, 8000  # resolution 1.25 Hz
    t = np.arange(n) / fs
    x = 3.0 * np.sin(2 * np.pi * 250.0 * t) + 0.5 * np.cos(2 * np.pi * 1000.0 * t) + 7.0
    for window in ("hann", "rect"):
        s = an.spectrum(x, fs, window=window)
        assert s.resolution == pytest.approx(1.25)
        assert s.at(250.0) == pytest.approx(3.0, rel=1e-9)
        assert s.at(1000.0) == pytest.approx(0.5, rel=1e-9)
        assert s.at(0.0) == pytest.approx(0.0, abs=1e-9)  # detrended
    peaks = an.find_peaks(an.spectrum(x, fs, window="rect"), 2)
    assert [f for f, _ in peaks] == [250.0, 1000.0]
    # A band keeps absolute frequencies; out of range is an error, not a wrapped index.
    band = an.spectrum(x, fs, window="rect").band(200.0, 450.0)
    assert band.at(250.0) == pytest.approx(3.0, rel=1e-9)
    with pytest.raises(ValueError, match="outside this spectrum"):
        band.at(100.0)
    # Nyquist: a unit cosine at fs/2 reads 1.
    nyq = np.cos(np.pi * np.arange(n))
    assert an.spectrum(nyq, fs, window="rect", detrend=False).at(fs / 2) == pytest.approx(1.0)


def test_sidebands_of_an_amplitude_modulated_carrier():
    # (1 + m cos(2 pi fm t)) sin(2 pi fc t): sidebands of m/2 at fc +- fm.
    fs, n, fc, fm, m = 8000.0, 8000, 1000.0, 12.5 * 4, 0.3
    t = np.arange(n) / fs
    x = (1 + m * np.cos(2 * np.pi * fm * t)) * np.sin(2 * np.pi * fc * t)
    sb = an.sidebands(an.spectrum(x, fs, window="rect"), fc, fm, orders=2)
    assert sb["levels"][0] == pytest.approx(1.0, rel=1e-9)
    assert sb["levels"][1] == pytest.approx(m / 2, rel=1e-9)
    assert sb["levels"][-1] == pytest.approx(m / 2, rel=1e-9)
    assert sb["levels"][2] == pytest.approx(0.0, abs=1e-9)
    assert sb["modulation_ratio"] == pytest.approx(m / math.sqrt(2), rel=1e-9)


def test_phase_statistics_and_theoretical_acceleration():
    model = cf.presets.paper()
    theta = np.linspace(0, 2 * np.pi, 36001)[:-1]
    theory = an.theoretical_follower_acceleration(model, theta)
    stats = an.phase_statistics(model, theta, theory)
    assert [s["phase"] for s in stats] == [
        "dwell 0-30 deg",
        "rise 30-180 deg",
        "dwell 180-210 deg",
        "return 210-360 deg",
    ]
    assert stats[0]["peak"] == 0.0 and stats[2]["rms"] == 0.0
    peak = model.omega**2 * 0.010 * (8 * np.pi / (np.pi + 2)) / np.radians(150) ** 2
    assert stats[1]["peak"] == pytest.approx(peak, rel=1e-9)


def test_contact_loss_intervals_from_flags():
    t = np.arange(10.0)
    flags = np.array([1, 1, 0, 0, 1, 1, 1, 0, 0, 0], dtype=bool)
    assert an.contact_loss_intervals(t, flags) == [(2.0, 4.0), (7.0, 9.0)]
    assert an.contact_loss_intervals(t, np.ones(10, bool)) == []


def test_last_revolutions_needs_a_step_dividing_the_period():
    model = cf.presets.paper()
    r = cf.simulate(model, revolutions=2, time_step=model.period / 4096, decimation=4)
    w = an.last_revolutions(r, model.period, 1)
    assert w.stop - w.start == 1024
    with pytest.raises(ValueError, match="does not divide the period"):
        an.last_revolutions(cf.simulate(model, revolutions=1, time_step=3e-6, decimation=100), model.period, 1)
    with pytest.raises(ValueError, match="signal must be finite"):
        an.spectrum(np.array([1.0, np.nan] * 8), 100.0)
    with pytest.raises(ValueError, match="window must be"):
        an.spectrum(np.ones(16), 100.0, window="kaiser")


def test_analysis_helpers_pick_the_named_contact_of_a_mechanism():
    """Two cams on one mechanism: each helper reads the named contact's program (a 5 mm and a 10 mm rise)."""
    b = cf.MechanismBuilder()
    for k, lift in ((1, 0.005), (2, 0.010)):
        b.add_dof(f"y{k}", 0.2, direction=(0, 1, 0))
        b.add_spring(f"spring{k}", f"y{k}", "ground", stiffness=2e4, preload=300.0)
        b.add_contact(
            f"cam{k}",
            cf.MotionProgram.paper_default(lift),
            cf.TranslatingRoller(0.03, 0.008),
            follower_dof=f"y{k}",
            stiffness=1e8,
        )
    m = b.build()
    theta = np.linspace(0, 2 * np.pi, 7201)[:-1]
    a1 = an.theoretical_follower_acceleration(m, theta, contact="cam1")
    a2 = an.theoretical_follower_acceleration(m, theta, contact="cam2")
    np.testing.assert_allclose(a2, 2 * a1, rtol=1e-12, atol=0)
    peak = m.omega**2 * 0.005 * (8 * np.pi / (np.pi + 2)) / np.radians(150) ** 2
    assert np.max(np.abs(a1)) == pytest.approx(peak, rel=1e-4)
    stats = an.phase_statistics(m, theta, a2, contact="cam2")
    assert stats[1]["peak"] == pytest.approx(np.max(np.abs(a2)))
    for call in (
        lambda: an.theoretical_follower_acceleration(m, theta),
        lambda: an.phase_statistics(m, theta, a1),
    ):
        with pytest.raises(ValueError, match=r"contact: name one of the mechanism's contacts \['cam1', 'cam2'\]"):
            call()
    with pytest.raises(ValueError, match="no contact named 'cam3'"):
        an.theoretical_follower_acceleration(m, theta, contact="cam3")
