# SPDX-License-Identifier: BSD-3-Clause
"""Events (docs/solvers.md): contact losses and re-contacts above the jump speed located by every method,
against scipy's event location on the 7-DOF equations written again in NumPy; the contact-loss intervals
they bound; the events' round trip through files and pickles."""

import pickle

import camfollower as cf
import numpy as np
import pytest
from camfollower.reference import NumpyCamFollower
from scipy.integrate import solve_ivp


@pytest.fixture(scope="module")
def fast_model():
    return cf.presets.paper(cf.Parameters(camshaft_speed_rpm=2000.0))  # above the jump speed (1329 rpm)


@pytest.fixture(scope="module")
def scipy_events(fast_model):
    """Zero crossings of the penetration of the independent NumPy model, by scipy's DOP853 at rtol 1e-12."""
    ref = NumpyCamFollower(fast_model)

    def gap(t, z):
        return ref.contact(t, z[:7])[1]

    sol = solve_ivp(ref.rhs, (0, fast_model.period), ref.initial(), method="DOP853", rtol=1e-12, atol=1e-15, events=gap)
    assert sol.status == 0
    times = sol.t_events[0]
    # The run starts in contact: losses and re-contacts alternate from a loss.
    kinds = ["lost" if i % 2 == 0 else "made" for i in range(len(times))]
    return times, kinds


@pytest.mark.parametrize("method", ["dormand_prince", "dop853", "radau"])
def test_explicit_events_against_scipy(fast_model, scipy_events, method):
    times, kinds = scipy_events
    assert len(times) >= 2
    r = cf.simulate(fast_model, revolutions=1, method=method, tolerance=1e-10, time_step=fast_model.period / 4096)
    assert [e[1] for e in r.events] == ["cam.contact"] * len(times)
    assert [e[2] for e in r.events] == kinds
    located = np.array([e[0] for e in r.events])
    assert np.max(np.abs(located - times)) < 1e-8 * fast_model.period
    # The contact-loss intervals start and end at the located instants.
    np.testing.assert_array_equal(np.array(r.contact_loss["cam"]).ravel(), located)


@pytest.mark.parametrize("method", ["newmark", "fox_goodwin"])
def test_newmark_events_within_their_steps(fast_model, scipy_events, method):
    times, kinds = scipy_events
    for steps in (8192, 3000):
        dt = fast_model.period / steps
        r = cf.simulate(fast_model, revolutions=1, method=method, time_step=dt)
        assert [e[2] for e in r.events] == kinds
        located = np.array([e[0] for e in r.events])
        assert np.max(np.abs(located - times)) < 0.5 * dt
        # The intervals start and end at the located instants, not at the steps that saw the change.
        np.testing.assert_array_equal(np.array(r.contact_loss["cam"]).ravel(), located)


def test_no_events_below_the_jump_speed():
    r = cf.simulate(cf.presets.paper(), revolutions=1, method="fox_goodwin", time_step=cf.presets.paper().period / 8192)
    assert r.events == []
    assert r.contact_loss == {"cam": []}


def test_events_survive_files_and_pickles(fast_model, tmp_path):
    r = cf.simulate(fast_model, revolutions=1, method="fox_goodwin", time_step=fast_model.period / 4096, decimation=64)
    assert r.events
    back = cf.Result.load(r.save(tmp_path / "run.npz"))
    assert back.events == r.events
    assert pickle.loads(pickle.dumps(r)).events == r.events


def test_mechanism_events_are_named_by_contact(fast_model):
    m = fast_model
    many = cf.simulate_many(
        [m, m], revolutions=1, method="dormand_prince", tolerance=1e-8, time_step=m.period / 2048, threads=2
    )
    one = cf.simulate(m, revolutions=1, method="dormand_prince", tolerance=1e-8, time_step=m.period / 2048)
    assert one.events and {e[1] for e in one.events} == {"cam.contact"}
    assert many[0].events == one.events and many[1].events == one.events
