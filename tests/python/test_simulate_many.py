# SPDX-License-Identifier: BSD-3-Clause
"""simulate_many: each case exactly as simulate() gives it alone, failures kept per case, cancellation,
bad input named."""

import camfollower as cf
import numpy as np
import pytest


def paper(scale=1.0):
    p = cf.Parameters()
    return cf.presets.paper(p.replace(contact_stiffness=scale * p.contact_stiffness))


RUN = dict(revolutions=0.25, method="fox_goodwin", decimation=16)


def fox_goodwin_step(m):
    return m.period / 4096


def one_dof():
    """A mechanism of another size than the preset's 7 DOFs, run in the same call."""
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5, direction=(0, 1, 0))
    b.add_spring("spring", "y", "ground", stiffness=2e4, preload=300.0)
    b.add_contact(
        "cam", cf.MotionProgram.paper_default(), cf.TranslatingRoller(0.03, 0.008, 0.0), follower_dof="y", stiffness=1e8
    )
    return b.build()


def test_every_case_matches_simulate_alone_bit_for_bit():
    systems = [paper(s) for s in (0.8, 1.0, 1.25)] + [one_dof()]
    systems.append(systems[1])  # the same immutable system twice
    results = cf.simulate_many(systems, threads=2, time_step=fox_goodwin_step(systems[0]), **RUN)
    assert len(results) == len(systems)
    for system, r in zip(systems, results):
        alone = cf.simulate(system, time_step=fox_goodwin_step(systems[0]), **RUN)
        assert r.channels == alone.channels
        np.testing.assert_array_equal(np.asarray(r._data), np.asarray(alone._data))
        assert r.stats["method"] == "fox_goodwin"
        assert r.stats["steps"] == alone.stats["steps"]
    # The stiffer contact gives a different force history: the cases ran their own systems.
    assert not np.array_equal(results[0]["cam.force"], results[2]["cam.force"])


def test_revolutions_count_each_systems_own_period():
    slow, fast = cf.Parameters(), cf.Parameters()
    fast = fast.replace(camshaft_speed_rpm=2 * slow.camshaft_speed_rpm)
    a, b = cf.presets.paper(slow), cf.presets.paper(fast)
    ra, rb = cf.simulate_many([a, b], revolutions=0.5, time_step=a.period / 4096, method="fox_goodwin")
    assert ra.t[-1] == pytest.approx(0.5 * a.period, rel=1e-9)
    assert rb.t[-1] == pytest.approx(0.5 * b.period, rel=1e-9)


def test_a_failing_case_is_raised_or_returned_and_the_others_run():
    # Fox-Goodwin is stable below sqrt(6) / omega_max: the step that suits the nominal contact is
    # refused for a contact 30x stiffer (its highest mode is ~5x higher), by that case alone.
    systems = [paper(), paper(30.0), paper()]
    step = systems[0].period / 4096
    with pytest.raises(ValueError, match=r"systems\[1\].*stability limit"):
        cf.simulate_many(systems, time_step=step, revolutions=0.1, method="fox_goodwin")
    out = cf.simulate_many(systems, time_step=step, revolutions=0.1, method="fox_goodwin", errors="return")
    assert isinstance(out[1], ValueError) and "time_step" in str(out[1])
    for r in (out[0], out[2]):
        assert isinstance(r, cf.Result) and r.stats["steps"] > 0


def test_progress_returning_false_cancels_the_rest():
    systems = [paper()] * 6
    calls = []

    def progress(done, total):
        calls.append((done, total))
        return False

    out = cf.simulate_many(
        systems,
        threads=1,
        revolutions=2.0,
        time_step=systems[0].period / 8192,
        method="fox_goodwin",
        decimation=64,
        progress=progress,
        progress_interval=1e-9,
    )
    assert calls and calls[0][1] == 6
    assert out[0] is not None and out[0].stats["cancelled"]
    assert all(r is None for r in out[1:])


def test_bad_input_is_refused_by_name():
    m = paper()
    with pytest.raises(ValueError, match="threads"):
        cf.simulate_many([m], threads=0, revolutions=0.1)
    with pytest.raises(ValueError, match="threads"):
        cf.simulate_many([m], threads=5000, revolutions=0.1)
    with pytest.raises(ValueError, match="errors"):
        cf.simulate_many([m], errors="ignore", revolutions=0.1)
    with pytest.raises(TypeError, match="initial_state"):
        cf.simulate_many([m], revolutions=0.1, initial_state=(np.zeros(7), np.zeros(7)))
    with pytest.raises(TypeError, match="time_stpe"):
        cf.simulate_many([m], revolutions=0.1, time_stpe=1e-5)
    with pytest.raises(ValueError, match=r"systems\[0\].*revolutions"):
        cf.simulate_many([m, m], revolutions=-1.0)
    with pytest.raises(TypeError, match=r"systems\[0\]"):
        cf.simulate_many(["not a system"], duration=0.01)
    # The output cap is shared by the cases: two cases get half of it each.
    one = cf.simulate(m, revolutions=0.05, time_step=m.period / 4096, method="fox_goodwin")
    need = np.asarray(one._data).nbytes
    cf.simulate_many(
        [m], revolutions=0.05, time_step=m.period / 4096, method="fox_goodwin", max_output_bytes=1.5 * need
    )
    with pytest.raises(ValueError, match="max_output_bytes"):
        cf.simulate_many(
            [m, m], revolutions=0.05, time_step=m.period / 4096, method="fox_goodwin", max_output_bytes=1.5 * need
        )
    assert cf.simulate_many([], revolutions=1.0) == []
