# SPDX-License-Identifier: BSD-3-Clause
"""Study answers that do not depend on how they were asked (issue: answers a designer can sign).

The jump speed is the first contact loss whatever the speed range; the steady state reaches the
accuracy asked, checked against an independent integrator (DOP853 at a tight tolerance from an
accurate orbit state), whatever step it starts from.
"""

import math
import warnings
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower import speed
from camfollower.periodic import periodic_steady_state
from camfollower.response import steady_response

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _independent_first_loss(m, speeds, steps=65536):
    """A brute-force scan with another scheme (Newmark's average acceleration at a fixed fine step, no
    accuracy ladder, no resonance grid): the first speed whose periodic state loses contact."""
    for rpm in speeds:
        mm = m.with_camshaft_speed_rpm(rpm)
        o = periodic_steady_state(
            mm,
            time_step=mm.period / steps,
            multipliers=False,
            fallback="transient",
            max_shooting_iterations=8,
            transient_max_revolutions=40,
        )
        if float(np.min(np.asarray(o.record(mm)["cam.force"]))) <= 0.0:
            return rpm
    return None


def test_jump_speed_is_the_first_loss_whatever_the_range():
    """The paper preset loses contact in a window that opens near 1303 rpm and closes below 1320 rpm,
    below the loss at ~1330 rpm that bisection over (1000, 2000) used to report as the jump speed."""
    m = cf.presets.paper()
    answers = []
    for speed_range in ((1000, 2000), (1290, 1370)):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            j = speed.jump_speed(m, speed_range, executor="processes", workers=2)
        answers.append(j)
        assert any(issubclass(w.category, speed.StudyWarning) and "2 windows" in str(w.message) for w in caught)
        assert len(j.windows) == 2 and j.windows[0].end_rpm < 1320 and 1325 < j.windows[1].start_rpm < 1335
        assert math.isnan(j.windows[1].end_rpm)
        lo, hi = j.bracket
        assert hi - lo <= 1e-3 * hi and j.rpm == hi
        assert j.accuracy <= 1e-3 and 0 < j.min_force_below_N < 20
        # Where it leaves: the return's deceleration (mirror of the rise's 121 deg).
        assert 250 < j.angle_deg < 290
        assert j.summary()["windows"][0]["start_rpm"] == j.rpm
    assert answers[0].rpm == pytest.approx(answers[1].rpm, abs=2e-3 * answers[0].rpm)
    assert 1300 < answers[0].rpm < 1310
    # An independent 1 rpm scan agrees within its resolution and the finder's tolerance.
    first = _independent_first_loss(m, np.arange(math.floor(answers[0].rpm) - 3.0, answers[0].rpm + 3.0, 1.0))
    assert first is not None and abs(first - answers[0].rpm) <= 1.0 + 2e-3 * first


def test_jump_speed_refuses_ranges_without_a_first_loss():
    m = cf.presets.paper()
    with pytest.raises(
        ValueError,
        match=r"no contact loss between 600 and 800 rpm .*smallest margin is .* N at "
        r".* rpm, at .* deg of cam angle",
    ):
        speed.jump_speed(m, (600, 800))
    with pytest.raises(ValueError, match="already lost at the lower speed 1400 rpm"):
        speed.jump_speed(m, (1400, 1500))
    with pytest.raises(ValueError, match=r"resolution must be a speed step in \(0, 200\] rpm"):
        speed.jump_speed(m, (600, 800), resolution=0)
    with pytest.raises(ValueError, match=r"accuracy must be a relative error in \[1e-06, 0.1\]"):
        speed.jump_speed(m, (600, 800), accuracy=0.5)


def test_a_scan_coarser_than_the_resonances_is_warned_about():
    m = cf.presets.paper()
    with pytest.warns(speed.StudyWarning, match="resolution 100 rpm is coarser than the model's resonances need"):
        speed.margin_scan(m, (700, 900), resolution=100.0, accuracy=0.05)


def test_resonance_speeds_are_where_shaft_orders_meet_the_modes():
    m = cf.presets.paper()
    f1 = float(m.modal_analysis(0.0)["frequencies_hz"][0])
    found = speed.resonance_speeds(m, 1000, 2000)
    # Every order from the first to the last excited one meets the first mode once in the range,
    # odd and even (the symmetric lift's rigid excitation lacks some; the flexible response has them).
    orders = {k for k, f, _ in found if f == f1}
    assert orders == {k for k in range(1, 200) if 1000 < 60 * f1 / k < 2000}
    assert all(r == pytest.approx(60 * f / k) for k, f, r in found)


@pytest.mark.parametrize("rpm", [750.0, 1200.0])
@pytest.mark.parametrize("accuracy", [1e-2, 1e-3, 1e-4])
def test_steady_response_reaches_the_accuracy_it_reports(rpm, accuracy):
    """Force and follower acceleration of the reported orbit against DOP853 (tolerance 1e-11) run over
    the same revolution from an accurate orbit state: within the reported estimate, which is within
    the accuracy asked."""
    m = cf.presets.paper().with_camshaft_speed_rpm(rpm)
    best = periodic_steady_state(m, time_step=m.period / 131072, gamma=0.5, beta=1 / 12, multipliers=False)
    for start in (4096, 8192):  # whatever the step it starts from
        row = steady_response(m, accuracy=accuracy, steps_per_revolution=start, keep_orbit=True, multipliers=False)
        assert row["accuracy_reached"] and row["accuracy"] <= accuracy and row["accuracy_target"] == accuracy
        n = row["steps_per_revolution"]
        ref = cf.simulate(
            m, revolutions=1, time_step=m.period / n, method="dop853", tolerance=1e-11, initial_state=(best.q, best.v)
        )
        got = row["orbit"].record(m)
        for channel in ("cam.force", "a.y2"):
            x, x_ref = np.asarray(got[channel]), np.asarray(ref[channel])
            error = np.max(np.abs(x - x_ref)) / np.max(np.abs(x_ref))
            assert error <= max(row["accuracy"], 1e-7), channel
        assert row["force_error_N"] == pytest.approx(row["accuracy"] * np.max(np.abs(got["cam.force"])), rel=1e-9)


@pytest.mark.parametrize("rpm", [600.0, 750.0])
def test_the_force_alone_reaches_its_accuracy_in_fewer_steps(rpm):
    """accuracy_of="force": the contact force of the reported orbit within the estimate against DOP853
    (as above), whatever the starting step; the search ends no later than with the acceleration in the
    estimate, and earlier on the paper preset at 1e-5, where the roller's ringing acceleration sets the
    step."""
    m = cf.presets.paper().with_camshaft_speed_rpm(rpm)
    best = periodic_steady_state(m, time_step=m.period / 131072, gamma=0.5, beta=1 / 12, multipliers=False)
    both = steady_response(m, accuracy=1e-5, keep_orbit=True, multipliers=False)
    assert both["accuracy_of"] == "force_and_acceleration"
    for start in (4096, 8192):
        row = steady_response(
            m, accuracy=1e-5, accuracy_of="force", steps_per_revolution=start, keep_orbit=True, multipliers=False
        )
        assert row["accuracy_reached"] and row["accuracy"] <= 1e-5 and row["accuracy_of"] == "force"
        assert row["steps_per_revolution"] < both["steps_per_revolution"]
        n = row["steps_per_revolution"]
        ref = cf.simulate(
            m, revolutions=1, time_step=m.period / n, method="dop853", tolerance=1e-11, initial_state=(best.q, best.v)
        )
        x, x_ref = np.asarray(row["orbit"].record(m)["cam.force"]), np.asarray(ref["cam.force"])
        assert np.max(np.abs(x - x_ref)) / np.max(np.abs(x_ref)) <= max(row["accuracy"], 1e-7)
    with pytest.raises(ValueError, match=r"accuracy_of must be 'force_and_acceleration' or 'force' .* got 'acc'"):
        steady_response(m, accuracy=1e-3, accuracy_of="acc")
    with pytest.raises(ValueError, match="accuracy_of must be"):
        speed.jump_speed(m, (1000.0, 1600.0), accuracy_of="forces")


def test_the_old_fixed_study_step_was_off_by_more_than_the_accuracy_now_reported():
    """At 4096 average-acceleration steps per revolution (the studies' old fixed scheme) the follower's
    acceleration is off by more than 1 % of its peak: the lightly damped fast mode rings with the wrong
    phase. The default study accuracy (1e-3) is met."""
    m = cf.presets.paper()
    best = periodic_steady_state(m, time_step=m.period / 131072, gamma=0.5, beta=1 / 12, multipliers=False)
    old = periodic_steady_state(m, time_step=m.period / 4096, multipliers=False)
    ref = cf.simulate(
        m, revolutions=1, time_step=m.period / 4096, method="dop853", tolerance=1e-11, initial_state=(best.q, best.v)
    )
    a_old, a_ref = np.asarray(old.record(m)["a.y2"]), np.asarray(ref["a.y2"])
    assert np.max(np.abs(a_old - a_ref)) / np.max(np.abs(a_ref)) > 1e-2
    row = steady_response(m)
    assert row["accuracy_target"] == 1e-3 and row["accuracy_reached"] and row["scheme"] == "fox_goodwin_matched"


def test_a_fixed_step_reports_its_accuracy_and_contact_loss_says_it_was_not_reached():
    m = cf.presets.paper()
    fixed = steady_response(m, steps_per_revolution=8192, multipliers=False)
    assert fixed["steps_per_revolution"] == 8192 and math.isnan(fixed["accuracy_target"])
    assert 0 < fixed["accuracy"] < 0.1 and fixed["accuracy_reached"]
    lost = steady_response(m.with_camshaft_speed_rpm(2000.0), fallback="transient", multipliers=False)
    assert lost["contact_lost"] and not lost["accuracy_reached"] and lost["accuracy"] > 1e-3
    with pytest.raises(ValueError, match=r"accuracy must be a relative error in \[1e-06, 0.1\]"):
        steady_response(m, accuracy=0.0)
    with pytest.raises(ValueError, match="steps_per_revolution must be even"):
        steady_response(m, steps_per_revolution=4097)


def test_any_channel_is_measured_like_the_contact():
    m = cf.presets.paper()
    row = steady_response(m, channels=["q.y4", "cam.force"], multipliers=False, accuracy=1e-2)
    assert row["channels"]["cam.force"]["min"] == pytest.approx(row["min_force_N"])
    assert row["channels"]["cam.force"]["min_angle_deg"] == pytest.approx(row["min_force_angle_deg"])
    y4 = row["channels"]["q.y4"]
    assert y4["max"] > y4["min"] and y4["dwell_residual"] >= 0
    with pytest.raises(ValueError, match="channels: no channel 'q.nothing'"):
        steady_response(m, channels=["q.nothing"], accuracy=1e-2)


def _independent_min_force(m, rpm, contact="cam", steps=65536):
    mm = m.with_camshaft_speed_rpm(rpm)
    o = periodic_steady_state(
        mm,
        time_step=mm.period / steps,
        multipliers=False,
        fallback="transient",
        max_shooting_iterations=8,
        transient_max_revolutions=40,
    )
    return float(np.min(np.asarray(o.record(mm)[f"{contact}.force"])))


@pytest.mark.parametrize(
    "example, speed_range", [("indexing_cam.toml", (340, 420)), ("flat_faced_table.toml", (2400, 2700))]
)
def test_first_loss_of_examples_against_an_independent_scan(example, speed_range):
    """The indexing cam loses contact first at a resonance of its slide (~112 Hz) with a shaft order,
    in a window below the speed where it is lost for good; the flat-faced tappet at its valve spring's
    surge (~390 Hz) with the 9th order, far below where it leaves for good. An independent Newmark
    scan 1 rpm apart brackets the same speed."""
    m = cf.load_config(EXAMPLES / example).mechanism
    contact = m.contact_names[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", speed.StudyWarning)
        j = speed.jump_speed(m, speed_range, executor="processes", workers=2)
    assert len(j.windows) >= 1 and j.windows[0].start_rpm == j.rpm
    first = None
    for rpm in np.arange(math.floor(j.rpm) - 2.0, j.rpm + 3.0, 1.0):
        if _independent_min_force(m, rpm, contact) <= 0.0:
            first = rpm
            break
    assert first is not None and first - 1.0 - 1e-3 * first <= j.rpm <= first + 1e-3 * first


def test_a_transient_that_diverges_is_an_error_not_a_state():
    """A follower thrown off its cam (a 15 mm rise squeezed into 40 deg at 750 rpm) and integrated at
    512 steps per revolution: the impacts blow the coarse transient up (|q| ~ 1e12 m). That must be a
    RuntimeError naming the step, not an orbit a finer run would start from (which then failed with
    "initial q must be in [-1000, 1000]")."""
    from camfollower.config import config_from_dict, load_config

    data = load_config(Path(__file__).resolve().parents[2] / "examples" / "translating_roller.toml").data
    rise = data["program"]["feed"]["segments"][1]
    rise["h"], rise["end"] = "15 mm", "80 deg"
    data["program"]["feed"]["segments"][2]["h"] = "15 mm"
    data["camshaft"]["speed"] = 750.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = config_from_dict(data, "examples").mechanism
    with pytest.raises(RuntimeError, match=r"diverged at time_step = 0\.00015625 s.*too coarse"):
        steady_response(m, steps_per_revolution=1024, multipliers=False, fallback="transient")
    # Finer, it is a contact-loss orbit like any other (not periodic: the transient route's answer).
    row = steady_response(m, steps_per_revolution=4096, multipliers=False, fallback="transient")
    assert row["contact_lost"] and row["min_force_N"] == 0.0


def test_a_model_too_large_for_shooting_goes_the_transient_route():
    """The 16-valve train (233 DOFs) is beyond shooting's dense monodromy (2n > 400) and runs on the
    sparse backend: the studies' scheme is average acceleration there (Fox-Goodwin was picked and the
    sparse backend refused it), and with fallback='transient' the steady state is the transient's."""
    from camfollower import _core
    from camfollower.config import load_config
    from camfollower.response import study_scheme

    m = load_config(Path(__file__).resolve().parents[2] / "examples" / "valve_train.toml").mechanism
    assert 2 * len(m.dof_names) > _core.SHOOTING_MAX_STATE_SIZE
    assert len(m.dof_names) >= _core.SPARSE_BACKEND_THRESHOLD
    # A step within half Fox-Goodwin's stability limit, where a dense model would get Fox-Goodwin.
    omega_max = 2.0 * math.pi * float(np.max(m.modal_analysis(0.0)["frequencies_hz"]))
    steps = int(2.0 * m.period * omega_max / (0.5 * math.sqrt(6.0))) + 1
    assert study_scheme(m, steps)["name"] == "newmark"
    with pytest.raises(ValueError, match="dense monodromy"):
        periodic_steady_state(m, time_step=m.period / 1024, multipliers=False)
    row = steady_response(m, steps_per_revolution=1024, multipliers=False, fallback="transient")
    assert row["method"] == "transient" and row["converged"] and not row["contact_lost"]


def test_one_stalled_halving_does_not_end_the_refinement():
    """The paper preset from rest at 600 rpm: the change between orbits goes 2.7e-3 (16384 steps),
    2.0e-3 (32768), then 1.9e-4 (65536), where the order shows. Stopping at the first halving that did
    not halve the change left the study at 2e-3 when 1e-4 was asked, while the same speed reached from
    a neighbour's orbit got there: the answer depended on where the sweep started.
    (With the period-matched scheme the change now falls steadily and 1e-4 is reached at 32768
    steps; the answers from rest and from the neighbour must agree within the accuracy.)"""
    m = cf.presets.paper().with_camshaft_speed_rpm(600)
    row = steady_response(m, accuracy=1e-4, multipliers=False)
    assert row["accuracy_reached"] and row["accuracy"] <= 1e-4
    neighbour = steady_response(m.with_camshaft_speed_rpm(650), accuracy=1e-4, multipliers=False, keep_orbit=True)
    warm = steady_response(m, accuracy=1e-4, multipliers=False, guess=neighbour["orbit"])
    assert warm["accuracy_reached"] and warm["accuracy"] <= 1e-4
    assert abs(warm["min_force_N"] - row["min_force_N"]) <= 2e-4 * row["max_force_N"]
    assert abs(warm["max_abs_acceleration"] - row["max_abs_acceleration"]) <= 2e-4 * row["max_abs_acceleration"]


@pytest.mark.parametrize("omega_dt", [1e-3, 0.05, 0.3, 0.8, 1.2])
def test_the_matched_beta_gives_the_exact_period(omega_dt):
    """Newmark (gamma = 1/2) on x'' = -w^2 x written out as its one-step map on (x, v, a); the angle of
    its complex eigenvalues is the discrete frequency times dt, which matched_beta makes exactly w dt.
    Fox-Goodwin (beta = 1/12) misses it by (w dt)^5 / 480 per step."""
    from camfollower.response import matched_beta

    def step_matrix(beta, w, h=1.0):
        columns = []
        for x0, v0, a0 in np.eye(3):
            a1 = -(w**2) * (x0 + h * v0 + h * h * (0.5 - beta) * a0) / (1.0 + beta * h * h * w**2)
            x1 = x0 + h * v0 + h * h * ((0.5 - beta) * a0 + beta * a1)
            v1 = v0 + h * 0.5 * (a0 + a1)
            columns.append([x1, v1, a1])
        return np.array(columns).T

    def discrete_angle(beta):  # of the unit-modulus pair (the third eigenvalue, of a's consistency, is ~0)
        eigenvalues = np.linalg.eigvals(step_matrix(beta, omega_dt))
        return max(abs(np.angle(eigenvalues[np.abs(eigenvalues) > 0.5])))

    beta = matched_beta(omega_dt)
    assert 1 / 12 < beta < 0.25
    assert discrete_angle(beta) == pytest.approx(omega_dt, rel=1e-9)
    if omega_dt >= 0.05:  # Fox-Goodwin's own period error, for contrast
        assert abs(discrete_angle(1 / 12) - omega_dt) > 0.1 * omega_dt**5 / 480


def test_the_studies_matched_scheme_beats_fox_goodwin_on_the_ringing_mode():
    """At 8192 steps per revolution the period-matched scheme's orbit is closer to the exact periodic
    response than Fox-Goodwin's in the roller's acceleration (the 12 kHz contact mode rings through the
    revolution): the reference is DOP853 at tolerance 1e-11 from a fine orbit."""
    from camfollower.response import scheme_settings, study_scheme

    m = cf.presets.paper()
    steps = 8192
    scheme = study_scheme(m, steps)
    assert scheme["name"] == "fox_goodwin_matched" and scheme["beta"] > 1 / 12
    assert scheme["matched_hz"] == pytest.approx(np.max(m.modal_analysis(0.0)["frequencies_hz"]))
    best = periodic_steady_state(m, time_step=m.period / 131072, gamma=0.5, beta=1 / 12, multipliers=False)
    ref = cf.simulate(
        m, revolutions=1, time_step=m.period / steps, method="dop853", tolerance=1e-11, initial_state=(best.q, best.v)
    )
    a_ref = np.asarray(ref["a.y2"])

    def error(**settings):
        o = periodic_steady_state(m, time_step=m.period / steps, multipliers=False, **settings)
        return np.max(np.abs(np.asarray(o.record(m)["a.y2"]) - a_ref)) / np.max(np.abs(a_ref))

    matched, fox_goodwin = error(**scheme_settings(scheme)), error(method="fox_goodwin")
    assert matched < 0.2 * fox_goodwin, (matched, fox_goodwin)
