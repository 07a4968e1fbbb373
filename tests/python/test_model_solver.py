# SPDX-License-Identifier: BSD-3-Clause
"""The 7-DOF model and the Newmark solver through the bindings, against independent routes:
scipy's Radau on the same equations written in NumPy, scipy.linalg.eigh on the exported matrices."""

import ctypes
import threading
import time

import camfollower as cf
import numpy as np
import pytest
import scipy.linalg
from camfollower.reference import NumpyCamFollower
from scipy.integrate import solve_ivp


@pytest.fixture(scope="module")
def model():
    return cf.presets.paper()


@pytest.fixture(scope="module")
def radau_reference(model):
    ref = NumpyCamFollower(model)
    sol = solve_ivp(
        ref.rhs,
        (0, model.period),
        ref.initial(),
        method="Radau",
        rtol=1e-10,
        atol=1e-13,
        jac=ref.jacobian,
        dense_output=True,
    )
    assert sol.status == 0
    return ref, sol


def test_initial_state_is_an_equilibrium_of_the_numpy_equations(model):
    ref = NumpyCamFollower(model)
    accel = ref.rhs(0.0, ref.initial())[7:]
    assert np.max(np.abs(accel)) < 1e-9  # m/s^2, against ~44 m/s^2 of follower acceleration
    g, delta = ref.contact(0.0, ref.q0)
    assert ref.kh * delta * g[0] == pytest.approx(1.4e4 * 0.013, rel=1e-9)


def test_one_revolution_matches_scipy_radau(model, radau_reference):
    ref, sol = radau_reference
    r = cf.simulate(model, revolutions=1)  # default time step 3 us
    z = sol.sol(r["t"])
    y4_err = np.max(np.abs(r["q"][:, 3] - z[3])) / np.max(np.abs(z[3]))
    forces = np.array([ref.kh * max(ref.contact(t, zi[:7])[1], 0.0) for t, zi in zip(r["t"][::50], z.T[::50])])
    f_err = np.max(np.abs(r["cam.force"][::50] - forces)) / np.max(forces)
    print(f"relative error vs Radau: y4 {y4_err:.2e}, contact force {f_err:.2e}")
    assert y4_err < 1e-6
    assert f_err < 1e-3


def test_halving_the_step_converges_at_second_order_towards_radau(model, radau_reference):
    _, sol = radau_reference
    errors = []
    for dt in (4e-6, 2e-6):
        r = cf.simulate(model, revolutions=1, time_step=dt)
        errors.append(np.max(np.abs(r["q"][:, 3] - sol.sol(r["t"])[3])))
    assert np.log2(errors[0] / errors[1]) == pytest.approx(2.0, abs=0.3)


def test_natural_frequencies_match_scipy_eigh(model):
    ref = NumpyCamFollower(model)
    for theta in (0.0, np.radians(100), np.radians(290)):
        q = np.array(model.static_equilibrium(theta))
        g, delta = ref.contact(theta / model.omega, q)
        assert delta > 0
        kt = ref.K + ref.kh * np.outer(g, g)
        f_scipy = np.sqrt(scipy.linalg.eigh(kt, ref.M, eigvals_only=True)) / (2 * np.pi)
        f_cf = model.modal_analysis(theta)["frequencies_hz"]
        np.testing.assert_allclose(f_cf, f_scipy, rtol=1e-10)


def test_results_are_numpy_views_with_decimation(model):
    r = cf.simulate(model, duration=0.01, time_step=1e-5, decimation=10)
    assert r["q"].shape == (101, 7) and r["t"].shape == (101,)
    assert r["q"].base is not None  # a view on the C++ buffer, not a copy
    assert r["cam.in_contact"].dtype == bool and r["cam.in_contact"].all()
    np.testing.assert_allclose(np.diff(r["t"]), 1e-4, rtol=1e-9)
    assert r["stats"]["steps"] == 1000


def test_contact_loss_reported_at_high_speed():
    fast = cf.presets.paper(cf.Parameters(camshaft_speed_rpm=3000))
    r = cf.simulate(fast, revolutions=1, time_step=1e-6, decimation=5)
    assert r.contact_loss["cam"], "the follower should lift off at 3000 rpm"
    assert np.all(r["cam.force"][~r["cam.in_contact"]] == 0.0)


def ran_alongside(fn):
    """Whether this thread ran Python code during the middle half of fn() running in another thread."""
    started, done = threading.Event(), threading.Event()
    window = {}

    def work():
        started.set()
        window["start"] = time.perf_counter()
        fn()
        window["end"] = time.perf_counter()
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    stamps = []
    while not done.is_set():
        stamps.append(time.perf_counter())
    worker.join()
    span = window["end"] - window["start"]
    return any(window["start"] + 0.25 * span <= s <= window["start"] + 0.75 * span for s in stamps)


def test_the_gil_is_released_during_a_run(model):
    # The probe itself: a foreign call through ctypes.PyDLL keeps the GIL, through CDLL it does not.
    assert not ran_alongside(lambda: ctypes.PyDLL(None).usleep(200000))
    assert ran_alongside(lambda: ctypes.CDLL(None).usleep(200000))
    assert ran_alongside(lambda: cf.simulate(model, revolutions=20, decimation=1000))


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(revolutions=1, time_step=0.0), "time_step must be finite and > 0"),
        (dict(revolutions=1, time_step=float("nan")), "time_step"),
        (dict(duration=1.0, revolutions=1), "exactly one of duration"),
        (dict(duration=-1.0), "duration must be finite and > 0"),
        (dict(revolutions=1, decimation=0), "decimation must be >= 1"),
        (dict(revolutions=1, method="hht", hht_alpha=0.2), "hht_alpha must be in"),
        (dict(revolutions=1, hht_alpha=-0.1), "hht_alpha applies to method 'hht' only"),
        (dict(revolutions=1, linear_solver="qr"), "linear_solver must be"),
        (dict(duration=100.0, max_output_bytes=1e6), "increase decimation"),
    ],
)
def test_bad_solver_input_raises_value_error(model, kwargs, message):
    with pytest.raises(ValueError, match=message):
        cf.simulate(model, **kwargs)


def test_conditionally_stable_scheme_refuses_a_step_beyond_its_limit(model):
    # beta = 1/12 is stable for omega_max dt < 2.45: about 2470 steps per revolution here.
    with pytest.raises(ValueError, match="exceeds the stability limit"):
        cf.simulate(model, revolutions=1, time_step=model.period / 2400, beta=1 / 12)
    r = cf.simulate(model, revolutions=1, time_step=model.period / 4096, beta=1 / 12, decimation=64)
    assert np.max(np.abs(r["q"][:, 0])) < 2e-6  # the camshaft stays at its ~1 um deflection


def test_hht_takes_its_own_gamma_and_beta_from_alpha(model):
    ref = cf.simulate(model, revolutions=1, time_step=model.period / 32768, decimation=8)
    r = cf.simulate(model, revolutions=1, time_step=model.period / 4096, method="hht", hht_alpha=-0.1)
    assert r.stats["method"] == "hht"
    assert np.max(np.abs(r["q"][:, 3] - ref["q"][:, 3])) < 1e-4 * 0.01
    # Newmark with HHT's gamma = 1/2 - alpha, beta = (1 - alpha)^2 / 4 but alpha = 0 is another scheme.
    nm = cf.simulate(model, revolutions=1, time_step=model.period / 4096, gamma=0.6, beta=0.3025)
    assert np.max(np.abs(nm["q"][:, 3] - r["q"][:, 3])) > 0.0
    # Given at all, a parameter the method does not read is refused (even at its default value).
    with pytest.raises(ValueError, match=r"gamma and beta apply to method 'newmark' only, got them with method 'hht'"):
        cf.simulate(model, revolutions=1, method="hht", hht_alpha=-0.1, gamma=0.5, beta=0.25)
    with pytest.raises(
        ValueError,
        match=r"hht_alpha applies to method 'hht' only, got it with method 'newmark' \(HHT-alpha is method 'hht'\)",
    ):
        cf.simulate(model, revolutions=1, hht_alpha=0.0)


def test_non_convergence_raises_runtime_error_with_context(model):
    with pytest.raises(RuntimeError, match=r"did not converge at t = .* s with time step .* residual"):
        cf.simulate(model, revolutions=1, max_iterations=1, max_halvings=2)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(roller_mass=0.0), "roller_mass must be finite and > 0"),
        (dict(rod_stiffness=-1.0), "rod_stiffness must be finite and > 0"),
        (dict(guide_stiffness=0.0), "guide_stiffness must be finite and > 0"),
        (dict(contact_stiffness=float("inf")), "contact_stiffness must be finite"),
        (dict(offset=0.05), r"\|offset\| < base_radius"),
        (dict(camshaft_speed_rpm=0.0), "camshaft_speed_rpm"),
        (dict(stiffness=1.0), "unknown parameter 'stiffness'"),
        (dict(contact_damping="viscous"), "contact_damping must be"),
    ],
)
def test_bad_parameters_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        cf.Parameters(**kwargs)


def test_parameters_by_name_and_defects_validation():
    p = cf.Parameters(contact_exponent=1.5, contact_stiffness=1e11)
    assert p.get("contact_exponent") == 1.5
    p = p.replace(roller_mass=0.08)
    assert p.to_dict()["roller_mass"] == 0.08
    with pytest.raises(ValueError, match="roller_mass"):
        p.replace(roller_mass=-1)
    with pytest.raises(AttributeError):
        p.roller_mass = 0.09  # immutable
    assert "contact_stiffness" in cf.Parameters.names()
    # Hertz point contact runs too (K in N/m^1.5), from its own static equilibrium.
    r = cf.simulate(cf.presets.paper(p), revolutions=0.5, decimation=100)
    assert np.all(np.isfinite(r["q"]))
    with pytest.raises(ValueError, match=r"eccentricity radius must be in \[0, 1000\] m, got -1e-06"):
        cf.CamEccentricity(-1e-6)
    with pytest.raises(ValueError, match=r"eccentricity radius must be in \[0, 1000\] m, got nan"):
        cf.CamEccentricity(float("nan"))
