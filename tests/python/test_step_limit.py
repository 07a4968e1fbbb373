# SPDX-License-Identifier: BSD-3-Clause
"""The step limit of Fox-Goodwin's processed velocity with damping (Mechanism.step_limit), against a
brute-force run of the scheme as docs/solvers.md writes it, mode by mode; and what the limit guards:
on the valve-train preset the shaft's stiffness-proportional damping made Fox-Goodwin grow without
bound at steps well within its undamped limit sqrt(6) / omega_max."""

import math

import camfollower as cf
import numpy as np
import pytest
from camfollower.response import study_scheme

FOX_GOODWIN_BETA = 1.0 / 12.0
MARGIN = 0.9  # the solver's margin on a step limit (the undamped one is 0.9 sqrt(6) / omega_max)


def _grows(omega, c, dt, beta=FOX_GOODWIN_BETA, steps=6000):
    """Processed Newmark (gamma = 1/2) on the mode a + c v + omega^2 q = 0 for `steps` steps of dt:
    the displacement follows the trapezoidal velocity vN, the damper sees v = vN - dt^2 / 12 a' with a'
    the three-point derivative (3 a1 - 4 a + a_prev) / (2 dt). True when the state at the end is ten
    times the largest of the first half (a slow mode's drift from the start only doubles)."""
    q, vn, a, a_prev = 1.0, 0.3 / dt, -0.7 / dt**2, 0.2 / dt**2  # every component excited

    def size():
        return max(abs(q), abs(vn) * dt, abs(a) * dt * dt)

    first_half = start = size()
    w2 = omega * omega
    for step in range(steps):
        if step % 100 == 0 and not size() <= 1e12 * start:
            return True  # before it overflows
        if step < steps // 2:
            first_half = max(first_half, size())
        # a1 + c v1 + w2 q1 = 0 with q1 and v1 linear in the unknown a1
        q_known = q + dt * vn + dt * dt * (0.5 - beta) * a
        v_known = vn + 0.5 * dt * a - dt / 24.0 * (-4.0 * a + a_prev)
        a1 = -(c * v_known + w2 * q_known) / (1.0 + c * (0.5 * dt - 3.0 * dt / 24.0) + w2 * beta * dt * dt)
        q, vn, a, a_prev = q_known + beta * dt * dt * a1, vn + 0.5 * dt * (a + a1), a1, a
    return not size() <= 10.0 * first_half


def _brute_force_limit(omega, c):
    """The largest stable step of the mode by bisection on _grows, to 0.1 %."""
    lo, hi = 0.0, (1.0 / (omega * math.sqrt(0.25 - FOX_GOODWIN_BETA)) if omega > 0.0 else 8.0 / c) * 1.01
    while hi - lo > 1e-3 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if _grows(omega, c, mid) else (mid, hi)
    return lo


def _modes(system):
    """The modes of the tangent at the quasi-static equilibrium at angle 0 with their modal damping
    phi' C phi (rad/s, 1/s)."""
    modal = system.modal_analysis(0.0)
    shapes = np.asarray(modal["mode_shapes"])
    damping = np.einsum("ik,ij,jk->k", shapes, np.asarray(system.damping), shapes)
    return 2.0 * math.pi * np.asarray(modal["frequencies_hz"]), np.maximum(damping, 0.0)


@pytest.mark.parametrize(
    "system",
    [
        cf.presets.paper_damped(),
        cf.presets.valve_train(engine_speed_rpm=6000, cylinders=1, firing_order=[1]),
    ],
    ids=["paper_damped", "valve_train_1_cylinder"],
)
def test_the_limit_is_the_brute_force_one_of_the_mode_that_sets_it(system):
    limit = system.step_limit(FOX_GOODWIN_BETA)
    omega, c = _modes(system)
    undamped = MARGIN * math.sqrt(6.0) / omega.max()
    assert limit["step"] < 0.7 * undamped  # damping lowers it here, by a third and by 94 %
    k = int(np.argmin(np.abs(omega - 2.0 * math.pi * limit["frequency_hz"])))
    assert limit["damping_ratio"] == pytest.approx(c[k] / (2.0 * omega[k]), rel=1e-6)
    assert limit["step"] / MARGIN == pytest.approx(_brute_force_limit(omega[k], c[k]), rel=3e-3)
    # no other mode grows at the limit without its margin (each stable a little below it)
    grows = [i for i in range(omega.size) if _grows(omega[i], c[i], 0.99 * limit["step"] / MARGIN)]
    assert grows == []


def test_beta_a_quarter_has_no_limit_and_a_beta_out_of_range_is_refused():
    system = cf.presets.paper_damped()
    assert math.isinf(system.step_limit(0.25)["step"])
    with pytest.raises(ValueError, match="beta"):
        system.step_limit(0.3)


@pytest.fixture(scope="module")
def valve_train():
    return cf.presets.valve_train(engine_speed_rpm=6000, cylinders=1, firing_order=[1])


def test_beyond_the_damped_limit_fox_goodwin_keeps_the_trapezoidal_velocity_and_says_why(valve_train):
    limit = valve_train.step_limit(FOX_GOODWIN_BETA)
    undamped = MARGIN * math.sqrt(6.0) / (2.0 * math.pi * limit["frequency_hz"])
    step = 1e-6  # within the undamped limit (1.2 us), beyond the damped one (0.15 us)
    assert limit["step"] < step < undamped
    runs = {
        method: cf.simulate(valve_train, duration=2e-4, time_step=step, method=method, linear_solver="dense_lu")
        for method in ("fox_goodwin", "auto")
    }
    for method, r in runs.items():
        assert r.stats["method"] == "fox_goodwin", method
        assert r.stats["velocity_choice"].startswith("trapezoidal velocity"), method
        assert "damping ratio 4.7" in r.stats["velocity_choice"], method
    # Bounded, and as accurate as average acceleration at a quarter of the step.
    fine = cf.simulate(valve_train, duration=2e-4, time_step=step / 4, method="newmark", linear_solver="dense_lu")
    valve = "q.c1v1.valve"
    peak = np.abs(np.asarray(fine[valve])).max()
    coarse = np.asarray(runs["fox_goodwin"][valve])
    assert np.abs(coarse - np.asarray(fine[valve])[::4]).max() < 1e-3 * peak
    # Beyond the undamped limit the step is refused.
    with pytest.raises(ValueError, match="exceeds the stability limit"):
        cf.simulate(
            valve_train, duration=2e-4, time_step=1.2 * undamped, method="fox_goodwin", linear_solver="dense_lu"
        )


def test_fox_goodwin_within_the_damped_limit_stays_bounded(valve_train):
    step = 0.95 * valve_train.step_limit(FOX_GOODWIN_BETA)["step"]
    r = cf.simulate(valve_train, duration=1e-4, time_step=step, method="fox_goodwin", linear_solver="dense_lu")
    reference = cf.simulate(valve_train, duration=1e-4, time_step=step, method="newmark", linear_solver="dense_lu")
    valve = "q.c1v1.valve"
    peak = np.abs(np.asarray(reference[valve])).max()
    assert np.abs(np.asarray(r[valve]) - np.asarray(reference[valve])).max() < 1e-3 * peak


def test_the_studies_take_average_acceleration_beyond_the_damped_limit(valve_train):
    limit = valve_train.step_limit(FOX_GOODWIN_BETA)["step"]
    # 65536 steps per revolution: omega_max dt = 1.15, within the studies' half of sqrt(6), but beyond
    # the damped limit; 262144: within both.
    assert valve_train.period / 65536 > limit > valve_train.period / 262144
    assert study_scheme(valve_train, 65536)["name"] == "newmark"
    assert study_scheme(valve_train, 262144)["name"] == "fox_goodwin_matched"


def test_the_sparse_backend_runs_fox_goodwin_with_the_trapezoidal_velocity_as_the_dense_one_does():
    # Four cams, 119 DOFs: linear_solver 'auto' takes the sparse backend.
    m = cf.presets.valve_train(engine_speed_rpm=6000, cylinders=2, firing_order=[1, 2])
    step = 1e-6  # within the undamped limit (1.2 us), beyond the processed velocity's
    sparse = cf.simulate(m, duration=2e-4, time_step=step, method="fox_goodwin")
    dense = cf.simulate(m, duration=2e-4, time_step=step, method="fox_goodwin", linear_solver="dense_lu")
    assert (sparse.stats["backend"], dense.stats["backend"]) == ("sparse", "dense")
    assert "sparse backend" in sparse.stats["velocity_choice"]
    assert dense.stats["velocity_choice"].startswith("trapezoidal velocity")
    for name in m.contact_names:
        force = np.asarray(dense[f"{name}.force"])
        assert np.abs(np.asarray(sparse[f"{name}.force"]) - force).max() < 1e-6 * np.abs(force).max(), name
    with pytest.raises(ValueError, match=r"exceeds the stability limit .*highest mode"):
        cf.simulate(m, duration=2e-4, time_step=1.5e-6, method="fox_goodwin")
