# SPDX-License-Identifier: BSD-3-Clause
"""Design studies: the periodic steady state by shooting against long transient runs, Floquet
multipliers against the transient's decay, the jump speed against transient runs on both sides and
the rigid-follower estimate, spring sizing, sweeps, Monte-Carlo statistics against closed forms,
executors (process pool, a real Dask LocalCluster) bit-identical to serial, the command line, and
bad input."""

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower import executors, speed
from camfollower import tolerance as tol
from camfollower.response import steady_response

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
STEPS = 4096


def orbit_of(m, **kw):
    return cf.periodic_steady_state(m, time_step=m.period / STEPS, **kw)


def transient_state(m, revolutions, **kw):
    r = cf.simulate(m, revolutions=revolutions, time_step=m.period / STEPS, decimation=STEPS, **kw)
    return np.array(r.q[-1]), np.array(r.v[-1])


@pytest.mark.parametrize("preset", ["paper_damped", "paper"])
def test_shooting_finds_the_orbit_a_long_transient_converges_to(preset):
    m = getattr(cf.presets, preset)()
    o = orbit_of(m, tolerance=1e-11)
    assert o.converged and o.stable
    assert 0.009 < o.q_scale < 0.011  # errors relative to the largest |q| (the lift) and |v| on the revolution
    # The paper's lightly damped lateral mode decays by ~0.97 per revolution: 1e-8 takes ~700.
    revolutions = 60 if preset == "paper_damped" else 1000
    r = cf.simulate(m, revolutions=revolutions, time_step=m.period / STEPS, decimation=STEPS)
    eq = np.abs(np.asarray(r.q) - o.q).max(axis=1) / o.q_scale
    ev = np.abs(np.asarray(r.v) - o.v).max(axis=1) / o.v_scale
    # Within 1e-8 over the last 50 revolutions (the transient still scatters by a few 1e-9 at rounding
    # level; before time was kept as t0 + n dt its drift made that 4e-8 in velocity).
    last = slice(-50, None)
    assert eq[last].max() < 1e-8
    assert ev[last].max() < 1e-8
    if preset == "paper":  # cheaper than the transient route by a wide margin
        assert o.revolutions < 0.1 * revolutions


def test_recorded_orbit_is_periodic_and_simulate_accepts_the_state():
    m = cf.presets.paper()
    o = orbit_of(m)
    r = o.record(m)
    q, v = np.asarray(r.q), np.asarray(r.v)
    assert r.rows == STEPS + 1
    assert np.abs(q[-1] - q[0]).max() < 1e-8 * np.abs(q).max()
    assert np.abs(v[-1] - v[0]).max() < 1e-8 * np.abs(v).max()
    with pytest.raises(ValueError, match="initial q must have 7 entries"):
        cf.simulate(m, revolutions=1, initial_state=(np.zeros(3), np.zeros(3)))
    with pytest.raises(ValueError, match="initial_state"):
        cf.simulate(m, revolutions=1, initial_state=5)


def test_floquet_spectral_radius_is_the_transient_decay_per_revolution():
    """The dominant multiplier sets how fast the transient dies: the settle history's change per
    revolution shrinks by |mu_max| each revolution (measured over revolutions 40-120)."""
    m = cf.presets.paper()
    o = orbit_of(m)
    r = cf.simulate(
        m,
        revolutions=1,
        time_step=m.period / STEPS,
        settle=True,
        settle_tolerance=1e-12,
        settle_max_revolutions=121,
        settle_dofs=["y2"],
        decimation=STEPS,
    )
    h = np.asarray(r.settle["history"])
    decay = (h[110:120].mean() / h[30:40].mean()) ** (1 / 80)
    assert o.spectral_radius == pytest.approx(decay, rel=5e-3)
    assert o.instability() == "stable"


@pytest.mark.parametrize("example, floor", [("swing_arm.toml", 1e-7), ("camshaft.toml", 5e-3)])
def test_variational_monodromy_against_centred_differences_of_the_revolution(example, floor):
    """The monodromy from the scheme's step sensitivities (one revolution) applied to random directions
    against centred differences of the revolution map (simulate from the orbit +- a small step): an
    oscillating follower, and a flexible camshaft (97 DOFs, well damped: its monodromy's entries are
    small and the centred differences carry ~1e-3 of rounding). Forward differences of shooting's own
    ("differences", 2n revolutions) are never closer."""
    m = cf.load_config(EXAMPLES / example).mechanism
    kw = dict(time_step=m.period / STEPS, method="newmark")
    var = cf.periodic_steady_state(m, monodromy="variational", tolerance=1e-10, **kw)
    fd = cf.periodic_steady_state(m, monodromy="differences", tolerance=1e-10, **kw)
    assert (fd.monodromy_method, var.monodromy_method) == ("differences", "variational")
    assert var.monodromy_at_orbit and var.variational_revolutions == var.monodromies
    assert var.revolutions < fd.revolutions
    assert np.abs(var.q - fd.q).max() <= 1e-8 * fd.q_scale
    n = len(var.q)

    def revolution(z):
        r = cf.simulate(m, revolutions=1, initial_state=(z[:n], z[n:]), decimation=STEPS, **kw)
        return np.concatenate([np.asarray(r.q[-1]), np.asarray(r.v[-1])])

    z = np.concatenate([var.q, var.v])
    scale = np.concatenate([np.full(n, var.q_scale), np.full(n, var.v_scale)])
    eps = 1e-5
    for d in np.random.default_rng(1).standard_normal((2, 2 * n)) * scale:
        centred = (revolution(z + eps * d) - revolution(z - eps * d)) / (2 * eps)
        peak = np.abs(centred).max()
        var_error = np.abs(var.monodromy @ d - centred).max() / peak
        fd_error = np.abs(fd.monodromy @ d - centred).max() / peak
        assert var_error < floor, (var_error, fd_error)
        assert var_error <= fd_error * 1.5 + 1e-9, (var_error, fd_error)


def test_monodromy_method_is_chosen_and_checked():
    m = cf.load_config(EXAMPLES / "grooved_cam.toml").mechanism
    kw = dict(time_step=m.period / STEPS, tolerance=1e-10)
    # A grooved cam's roller chatters between its flanks: the variational equations miss the impacts
    # within steps (their monodromy is off by a factor ~3 against differences), so "auto" goes over to
    # differences once a variational Newton step does not halve the mismatch, and converges.
    chatter = cf.periodic_steady_state(m, method="fox_goodwin", **kw)
    assert chatter.converged and chatter.monodromy_method == "differences"
    assert chatter.variational_revolutions >= 1  # it tried them first
    with pytest.raises(RuntimeError, match="did not converge"):
        cf.periodic_steady_state(m, method="fox_goodwin", monodromy="variational", **kw)
    explicit = cf.periodic_steady_state(m, time_step=m.period / STEPS, method="dormand_prince", tolerance=1e-9)
    assert explicit.monodromy_method == "differences"
    with pytest.raises(ValueError, match="monodromy 'variational' needs the Newmark family"):
        cf.periodic_steady_state(m, time_step=m.period / STEPS, method="dormand_prince", monodromy="variational")
    with pytest.raises(ValueError, match="monodromy must be 'auto', 'variational' or 'differences', got 'exact'"):
        cf.periodic_steady_state(m, monodromy="exact", **kw)


def test_shooting_failure_is_reported_and_the_transient_fallback_answers():
    m = cf.presets.paper().with_camshaft_speed_rpm(2000)  # far above the jump: the follower bounces
    with pytest.raises(RuntimeError, match=r"did not converge.*mismatch.*fallback='transient'"):
        orbit_of(m, max_shooting_iterations=3)
    o = orbit_of(m, max_shooting_iterations=3, fallback="transient", transient_max_revolutions=20)
    assert o.method == "transient"
    assert len(o.multipliers) == 0
    with pytest.raises(ValueError, match="divide"):
        cf.periodic_steady_state(m, time_step=m.period / 1000.5)
    with pytest.raises(ValueError, match="fallback"):
        cf.periodic_steady_state(m, time_step=m.period / 1000, fallback="maybe")
    with pytest.raises(ValueError, match="shooting tolerance"):
        cf.periodic_steady_state(m, time_step=m.period / 1000, tolerance=-1)


def test_jump_speed_of_the_paper_mechanism_against_transients_and_the_rigid_follower():
    m = cf.presets.paper()
    j = speed.jump_speed(m, (1000, 2000), tolerance=2e-3)
    lo, hi = j.bracket
    assert hi - lo <= 2e-3 * hi

    # The transient route on both sides, 5 % away: run until settled (or 600 revolutions: the start-up
    # transient of the lightly damped mechanism loses contact below the jump speed too), then two
    # revolutions: contact kept below, lost above.
    def transient(rpm):
        mm = m.with_camshaft_speed_rpm(rpm)
        return cf.simulate(
            mm,
            revolutions=2,
            time_step=mm.period / STEPS,
            decimation=64,
            settle=True,
            settle_tolerance=1e-5,
            settle_max_revolutions=600,
        )

    below, above = transient(0.95 * j.rpm), transient(1.05 * j.rpm)
    assert below.settle["settled"]
    assert not below.contact_loss["cam"]
    assert above.contact_loss["cam"]
    # Rigid follower (masses y2..y4 moving with the lift): the contact force is
    # k_s (delta0 + h) + m omega^2 h''; it first reaches 0 at omega^2 = min over the deceleration of
    # k_s (delta0 + h) / (-m h''), at that cam angle.
    p = cf.Parameters()
    prog = cf.MotionProgram.paper_default()
    th = np.linspace(0, 2 * np.pi, 20001)
    e = prog.evaluate(th)
    h, d2h = np.asarray(e["h"]), np.asarray(e["d2h"])
    mass = p.get("roller_mass") + p.get("follower_rod_mass") + p.get("follower_mass")
    spring = p.get("spring_stiffness") * (p.get("spring_preload_deflection") + h)
    ratio = np.where(d2h < 0, spring / (-mass * np.minimum(d2h, -1e-300)), np.inf)
    k = int(np.argmin(ratio))
    rigid_rpm = math.sqrt(ratio[k]) * 60 / (2 * math.pi)
    assert j.rpm == pytest.approx(rigid_rpm, rel=0.1)
    # The rise (30-180 deg) and the return (210-360 deg) are mirror images: the rigid follower is
    # equally close to leaving at both decelerations; the flexible one leaves at one of them.
    critical = np.degrees(th[ratio <= 1.0001 * ratio[k]])
    assert np.min(np.abs(critical - j.angle_deg)) < 10
    with pytest.raises(ValueError, match="two increasing speeds"):
        speed.jump_speed(m, (2000, 1000))


def test_an_example_follower_that_jumps():
    """The flat-faced tappet of examples/flat_faced_table.toml leaves its cam at a speed the sweep
    finds, with the cam angle."""
    case = cf.load_config(EXAMPLES / "flat_faced_table.toml")
    m = case.mechanism
    rpm = m.camshaft_speed_rpm
    rows = speed.margin_curve(m, [rpm, 4 * rpm], executor="serial", progress=False)
    assert not rows[0]["contact_lost"] and rows[1]["contact_lost"]
    j = speed.jump_speed(m, (rpm, 4 * rpm), tolerance=5e-3)
    assert rpm < j.rpm < 4 * rpm
    assert 0 <= j.angle_deg < 360


def test_spring_sizing_keeps_the_stated_margin():
    def build(rate, preload):
        return tol.PaperCase()({"spring_stiffness": rate, "spring_preload_deflection": preload / rate})

    margin, rpm = 40.0, 1300.0
    (s,) = speed.size_spring(build, rpm, margin, [14000.0], preload_guess=150.0)
    assert s.min_force_N >= margin - 0.5
    check = steady_response(build(14000.0, s.preload).with_camshaft_speed_rpm(rpm))
    assert check["min_force_N"] == pytest.approx(margin, abs=1.0)
    short = steady_response(build(14000.0, 0.95 * s.preload).with_camshaft_speed_rpm(rpm))
    assert short["min_force_N"] < margin
    with pytest.raises(ValueError, match="margin"):
        speed.size_spring(build, rpm, -1.0, [14000.0])
    with pytest.raises(ValueError, match="rates"):
        speed.size_spring(build, rpm, 10.0, [0.0])


def test_speed_sweep_marks_resonances_at_the_shaft_orders():
    m = cf.presets.paper_damped()
    sweep = speed.speed_sweep(m, [600, 750, 900], executor="serial", progress=False)
    assert sweep["spectrum"].shape == (64, 3)
    for k, f, rpm in sweep["resonances"]:
        assert k * rpm / 60 == pytest.approx(f)
        assert 600 <= rpm <= 900
    # the first harmonic of the contact force follows the spring and inertia forces: it grows with speed
    # (independent check: the rigid follower's first harmonic m omega^2 h''_1 + k h_1 rises with omega^2)
    assert sweep["spectrum"][1, 2] != sweep["spectrum"][1, 0]
    fig = speed.plot_waterfall(sweep)
    assert fig.axes


def test_monte_carlo_draws_are_reproducible_per_case():
    build = tol.PaperCase()
    tols = {"contact_stiffness": tol.Normal(0.05, relative=True), "eccentricity": tol.TruncatedNormal(5e-6, 0.0, 2e-5)}
    a = tol.monte_carlo(build, tols, cases=3, seed=11, executor="serial", progress=False)
    b = tol.monte_carlo(build, tols, cases=5, seed=11, executor="serial", progress=False)
    for ra, rb in zip(a.rows, b.rows):
        assert ra == rb
    rng = np.random.default_rng([11, 2])
    assert a.rows[2]["contact_stiffness"] == 1.9e8 * (1 + 0.05 * rng.standard_normal())
    assert all(0 <= r["eccentricity"] <= 2e-5 for r in b.rows)
    assert all(r["ok"] and r["converged"] for r in b.rows)


def test_monte_carlo_statistics_against_closed_forms():
    """Sensitivities and summary on rows with a known linear law y = 2 x1 - x2 (+ small noise): the
    standardized coefficients are 2 sd1 / sd_y and -sd2 / sd_y, the correlations the same for
    independent inputs."""
    rng = np.random.default_rng(5)
    x1, x2 = rng.normal(0, 1, 4000), rng.normal(0, 2, 4000)
    y = 2 * x1 - x2 + rng.normal(0, 1e-3, 4000)
    rows = [
        {"case": i, "seed": 5, "a": x1[i], "b": x2[i], "min_force_N": y[i], "ok": True, "error": ""}
        for i in range(4000)
    ]
    r = tol.MonteCarloResult(rows=rows, nominal={"min_force_N": 0.0}, parameters=["a", "b"], metrics=["min_force_N"])
    sd_y = math.sqrt(4 * 1 + 4)
    s = {d["parameter"]: d for d in r.sensitivities("min_force_N")}
    assert s["a"]["standardized_coefficient"] == pytest.approx(2 / sd_y, abs=0.03)
    assert s["b"]["standardized_coefficient"] == pytest.approx(-2 / sd_y, abs=0.03)
    assert s["a"]["correlation"] == pytest.approx(2 / sd_y, abs=0.03)
    m = r.summary()["metrics"]["min_force_N"]
    assert m["std"] == pytest.approx(sd_y, rel=0.05)
    assert m["p50"] == pytest.approx(0.0, abs=0.15)


def test_bad_tolerances_are_refused():
    build = tol.PaperCase()
    with pytest.raises(ValueError, match="std must be >= 0"):
        tol.Normal(-1.0)
    with pytest.raises(ValueError, match="low <= high"):
        tol.Uniform(1.0, 0.0)
    with pytest.raises(ValueError, match="less than 1e-3"):
        tol.TruncatedNormal(1.0, 10.0, 11.0)
    # a uniform spread that reaches a negative stiffness: refused before anything runs, naming it
    with pytest.raises(ValueError, match="contact_stiffness.*refuses"):
        tol.monte_carlo(
            build, {"contact_stiffness": tol.Uniform(-2e8, 0.0)}, cases=2, executor="serial", progress=False
        )
    with pytest.raises(ValueError, match="unknown parameter 'stifness'"):
        tol.monte_carlo(build, {"stifness": tol.Normal(1.0)}, cases=2, executor="serial")
    with pytest.raises(ValueError, match="cases"):
        tol.monte_carlo(build, {"roller_mass": tol.Normal(0.001)}, cases=0)


def _crash_on_three(x):
    if x == 3:
        os._exit(3)  # a worker dying in compiled code, as far as the pool can tell
    if x == 5:
        raise ValueError("case five is bad")
    return x * x


def test_executors_keep_the_other_results_when_a_case_fails_or_kills_its_worker():
    out = executors.run_cases(_crash_on_three, range(8), workers=2, progress=False)
    assert [o.ok for o in out] == [True, True, True, False, True, False, True, True]
    assert out[3].error == "worker crashed"
    assert "case five is bad" in out[5].error
    assert [o.value for o in out if o.ok] == [0, 1, 4, 16, 36, 49]
    serial = executors.run_cases(_crash_on_three, [0, 1, 5], executor="serial", progress=False)
    assert [o.ok for o in serial] == [True, True, False]


def test_unreachable_scheduler_fails_fast():
    pytest.importorskip("distributed")
    t0 = time.perf_counter()
    with pytest.raises(RuntimeError, match="cannot reach the Dask scheduler"):
        executors.run_cases(abs, [1, 2], executor="tcp://127.0.0.1:9", connect_timeout=2.0, progress=False)
    assert time.perf_counter() - t0 < 15


def _in_thread(seconds, fn):
    """fn() in a daemon thread: (returned, raised), or a test failure after `seconds` (a hang)."""
    import threading

    box = {}

    def run():
        try:
            box["value"] = fn()
        except BaseException as e:  # noqa: BLE001 - handed to the test
            box["error"] = e

    t = threading.Thread(target=run, daemon=True)
    t.start()
    t.join(seconds)
    assert not t.is_alive(), f"still running after {seconds} s"
    return box.get("value"), box.get("error")


class _FakeScheduler:
    """A TCP server on 127.0.0.1 that is not a Dask scheduler: it accepts and stays silent, sends a
    frame header announcing 3.5e18 bytes (then nothing), or closes every connection at once."""

    def __init__(self, behaviour):
        import socket
        import threading

        self.behaviour, self.sock, self.open = behaviour, socket.create_server(("127.0.0.1", 0)), []
        self.sock.settimeout(0.1)
        self.port = self.sock.getsockname()[1]
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self):
        import socket
        import struct

        while not self.stop.is_set():
            try:
                conn, _ = self.sock.accept()
            except socket.timeout:
                continue
            if self.behaviour == "closes":
                conn.close()
                continue
            if self.behaviour == "garbage":
                conn.sendall(struct.pack("<Q", 0x3100000000000000) + b"\xff" * 8)
            self.open.append(conn)

    def close(self):
        self.stop.set()
        self.thread.join(5)
        for c in self.open:
            c.close()
        self.sock.close()


@pytest.mark.parametrize("behaviour", ["silent", "garbage", "closes"])
def test_a_peer_that_is_not_a_dask_scheduler_fails_within_the_timeout(behaviour):
    """Before, a silent peer hung Client() for ever (distributed bounds the TCP connection, not the
    handshake) and a huge frame length raised MemoryError out of the command line."""
    pytest.importorskip("distributed")
    server = _FakeScheduler(behaviour)
    address = f"tcp://127.0.0.1:{server.port}"
    try:
        t0 = time.perf_counter()
        value, error = _in_thread(
            20, lambda: executors.run_cases(abs, [1, 2], executor=address, connect_timeout=2.0, progress=False)
        )
        elapsed = time.perf_counter() - t0
    finally:
        server.close()
    assert isinstance(error, RuntimeError), (value, error)
    assert address in str(error) and "Dask scheduler" in str(error)
    assert elapsed < 2.0 + 5.0  # the timeout, plus tearing the half-made client down


def _exit_below_two(x):
    if x < 2:
        os._exit(3)  # kills the Dask worker process, as a crash in compiled code would
    return x * x


def test_dask_keeps_the_healthy_cases_when_others_kill_their_workers():
    """Two workers, the cases 0 and 1 each kill theirs: the cases 2 and 3 queued behind them on the
    same workers died with them (KilledWorker), and must be run again, as the process pool does."""
    dask = pytest.importorskip("dask")
    pytest.importorskip("distributed")
    # One failure per task, as camfollower's own dask:N clusters do: a remote scheduler's default (3
    # reruns per task) only spreads the same deaths wider.
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        out = executors.run_cases(_exit_below_two, range(4), executor="dask:2", progress=False)
    assert [o.ok for o in out] == [False, False, True, True], [o.error for o in out]
    assert [o.value for o in out[2:]] == [4, 9]
    assert out[0].error == out[1].error == "worker crashed"


_ORPHAN_STUDY = """
import os, sys, time
from camfollower import executors

def case(folder):
    open(os.path.join(folder, str(os.getpid())), "w").close()
    time.sleep(120)

if __name__ == "__main__":
    executors.run_cases(case, [sys.argv[1]] * 2, workers=2, progress=False)
"""


def _running(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rpartition(")")[2].split()[0] != "Z"  # a zombie is dead, just not reaped
    except FileNotFoundError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_pool_workers_die_when_the_study_process_is_killed(tmp_path):
    import signal

    script = tmp_path / "study.py"
    script.write_text(_ORPHAN_STUDY)
    study = subprocess.Popen([sys.executable, str(script), str(tmp_path)])
    workers = []
    try:
        deadline = time.monotonic() + 60
        while len(workers) < 2 and time.monotonic() < deadline and study.poll() is None:
            time.sleep(0.05)
            workers = [int(p.name) for p in tmp_path.iterdir() if p.name.isdigit()]
        assert len(workers) == 2, "the pool's workers did not start"
        study.send_signal(signal.SIGKILL)
        study.wait(10)
        deadline = time.monotonic() + 5
        while any(_running(w) for w in workers) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(_running(w) for w in workers), "pool workers outlived the killed study"
    finally:
        if study.poll() is None:
            study.kill()
        for w in workers:  # only the workers this test started, should they have survived
            if _running(w):
                os.kill(w, signal.SIGKILL)


@pytest.mark.parametrize(
    "spec",
    [
        "dask:abc",
        "dask:0",
        "dask:-2",
        "dask:1.5",
        "dask: 2",
        "dask:",
        "dask:١",
        "dask:5000",
        "tcp://host",
        "tcp://:8786",
        "tcp://host:0",
        "tcp://host:70000",
        "host:8786",
        "http://host:8786",
        "Serial",
        "process",
        "",
    ],
)
def test_bad_executor_strings_are_refused_before_anything_runs(spec):
    for items in ([1, 2], []):  # up front: even a study with no case
        with pytest.raises(ValueError, match=r"^executor(?=.*'dask:N')(?=.*tcp://host:port)"):
            executors.run_cases(abs, items, executor=spec, progress=False)


def test_bad_executor_types_worker_counts_and_timeouts_are_refused():
    for bad in (3, 2.5, ["serial"], b"serial", abs):
        with pytest.raises(TypeError, match=r"executor must be None or 'processes'.*dask.distributed.Client"):
            executors.run_cases(abs, [], executor=bad)
    for workers in (True, 2.0, "2"):
        with pytest.raises(TypeError, match="workers must be an integer"):
            executors.run_cases(abs, [1], workers=workers, executor="serial")
    for workers in (0, -1):
        with pytest.raises(ValueError, match="workers must be an integer >= 1"):
            executors.run_cases(abs, [1], workers=workers)
    # A count the executor would ignore: the Dask and serial executors have their own workers.
    for executor in ("serial", "dask:2", "tcp://127.0.0.1:9"):
        with pytest.raises(ValueError, match="workers=2 sizes the process pool.*dask:N"):
            executors.run_cases(abs, [1], workers=2, executor=executor)
    assert [o.value for o in executors.run_cases(abs, [-1], workers=1, executor="serial", progress=False)] == [1]
    for timeout in (0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="connect_timeout must be a finite number of seconds > 0"):
            executors.run_cases(abs, [1], executor="tcp://127.0.0.1:9", connect_timeout=timeout)
    with pytest.raises(ValueError, match=r"address: 'dask:x' needs N"):
        executors.connect("dask:x")
    with pytest.raises(ValueError, match="address must be a Dask scheduler address"):
        executors.connect("serial")


class _NeverBuilt:
    """A Monte-Carlo builder that fails the test if the study gets as far as building a model."""

    def nominal(self, name):
        return 1.0

    def __call__(self, values):
        raise AssertionError("a model was built before the executor was checked")


def test_monte_carlo_checks_its_executor_before_building_a_model():
    for executor, workers in (("dask:abc", None), ("dask:2", 4), (object(), None)):
        with pytest.raises((ValueError, TypeError), match="executor"):
            tol.monte_carlo(
                _NeverBuilt(), {"x": tol.Normal(0.1)}, cases=2, executor=executor, workers=workers, progress=False
            )


def test_command_line_refuses_a_bad_scheduler_before_reading_the_config(tmp_path, capsys):
    from camfollower import cli

    missing = str(tmp_path / "missing.toml")  # never read: the option is refused first
    for spec in ("dask:abc", "tcp://host", "dask:0"):
        assert cli.main(["montecarlo", missing, "--scheduler", spec, "-o", str(tmp_path / "out")]) == 2  # usage
        err = capsys.readouterr().err
        assert err.startswith("camfollower: error: --scheduler") and "'dask:N'" in err, err
        assert "missing.toml" not in err and "Traceback" not in err


def test_monte_carlo_on_a_dask_local_cluster_equals_serial_bit_for_bit():
    distributed = pytest.importorskip("distributed")
    build = tol.PaperCase()
    tols = {
        "contact_stiffness": tol.Normal(0.05, relative=True),
        "spring_stiffness": tol.Uniform(-0.05, 0.05, relative=True),
    }
    serial = tol.monte_carlo(build, tols, cases=6, seed=1, executor="serial", progress=False)
    with (
        distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster,
        distributed.Client(cluster) as client,
    ):
        dask = tol.monte_carlo(build, tols, cases=6, seed=1, executor=client, progress=False)
    pool = tol.monte_carlo(build, tols, cases=6, seed=1, workers=2, progress=False)
    assert dask.rows == serial.rows
    assert pool.rows == serial.rows


def test_command_line_sweep_and_montecarlo(tmp_path):
    cfg = EXAMPLES / "paper_studies.toml"
    env = {**os.environ, "PYTHONWARNINGS": "ignore"}
    s = subprocess.run(
        [
            sys.executable,
            "-m",
            "camfollower",
            "sweep",
            str(cfg),
            "--rpm",
            "700",
            "1250",
            "--jump",
            "1000",
            "2000",
            "--workers",
            "1",
            "--no-progress",
            "-o",
            str(tmp_path / "sweep"),
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert s.returncode == 0, s.stderr
    summary = json.loads((tmp_path / "sweep" / "summary.json").read_text())
    assert 1200 < summary["jump"]["rpm"] < 1500
    assert all((tmp_path / "sweep" / f).is_file() for f in summary["files"])
    assert "jump speed" in s.stdout
    # Every loss window printed, as the summary has them (the preset's first one opens at ~1304 rpm).
    windows = summary["jump"]["windows"]
    assert windows and s.stdout.count("  contact lost from ") == len(windows)
    assert f"contact lost from {windows[0]['start_rpm']:.1f} rpm" in s.stdout
    mc = subprocess.run(
        [
            sys.executable,
            "-m",
            "camfollower",
            "montecarlo",
            str(cfg),
            "--cases",
            "6",
            "--workers",
            "1",
            "--no-progress",
            "-o",
            str(tmp_path / "mc"),
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert mc.returncode == 0, mc.stderr
    summary = json.loads((tmp_path / "mc" / "summary.json").read_text())
    assert summary["cases"] == 6 and summary["failed"] == 0
    lines = (tmp_path / "mc" / "cases.csv").read_text().splitlines()
    assert len(lines) == 7 and "preset.parameters.contact_stiffness" in lines[0]
    bad = tmp_path / "bad.toml"
    bad.write_text(cfg.read_text().replace("cases = 200", "cases = 200\nsamples = 3"))
    r = subprocess.run(
        [sys.executable, "-m", "camfollower", "montecarlo", str(bad), "-o", str(tmp_path / "x")],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert r.returncode == 1 and "montecarlo.samples: unknown key" in r.stderr


def test_cancellation_keeps_what_finished():
    import threading

    stop = threading.Event()

    def case(x):
        if x == 1:
            stop.set()  # e.g. a GUI's cancel button, pressed while case 1 runs
        return x

    out = executors.run_cases(case, range(5), executor="serial", cancel=stop, progress=False)
    assert [o.ok for o in out] == [True, True, False, False, False]
    assert out[4].error == "cancelled"


def test_motion_laws_side_by_side():
    """Two programs with the same rise and return angles: the rigid follower's peak accelerations
    are in the ratio of the laws' textbook coefficients (cycloidal 2 pi, modified trapezoid
    8 pi / (pi + 2) = 4.888); residual vibration is reported for both dwells."""

    def program(law):
        r = math.radians
        return cf.MotionProgram(
            [
                cf.Segment(cf.MotionLaw.dwell(), 0.0, r(30), 0.0, 0.0),
                cf.Segment(law, r(30), r(180), 0.0, 0.010),
                cf.Segment(cf.MotionLaw.dwell(), r(180), r(210), 0.010, 0.010),
                cf.Segment(law, r(210), 2 * math.pi, 0.010, 0.0),
            ]
        )

    rows = speed.compare_programs(
        lambda p: cf.presets.paper(program=p),
        {
            "modified trapezoid": program(cf.MotionLaw.modified_trapezoid()),
            "cycloidal": program(cf.MotionLaw.cycloidal()),
        },
        750,
        executor="serial",
        progress=False,
    )
    by = {r["program"]: r for r in rows}
    ratio = by["cycloidal"]["rigid_max_abs_acceleration"] / by["modified trapezoid"]["rigid_max_abs_acceleration"]
    assert ratio == pytest.approx(2 * math.pi / (8 * math.pi / (math.pi + 2)), rel=1e-3)
    for r in rows:
        assert [round(d["start_deg"]) for d in r["dwells"]] == [0, 180]
        assert r["dwell_residual"] == max(d["peak_to_peak"] for d in r["dwells"]) > 0
    assert by["cycloidal"]["max_abs_acceleration"] > by["modified trapezoid"]["max_abs_acceleration"]
