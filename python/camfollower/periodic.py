# SPDX-License-Identifier: BSD-3-Clause
"""The periodic steady state of a cam mechanism, found directly (shooting) instead of by waiting.

A cam turning at constant speed forces the mechanism periodically; after the start-up transient has
died out the response repeats every revolution. :func:`periodic_steady_state` finds that response by
Newton's method on the state at the start of a revolution (docs/studies.md): it costs a fixed number
of revolutions (``2 n`` per monodromy matrix for ``n`` DOFs, plus one per iteration) however lightly
damped the mechanism is, where the transient route needs as many revolutions as its slowest mode takes
to decay. For the Newmark family on the dense backend the monodromy comes from the scheme's variational
equations carried through one revolution (about three revolutions' time) instead of ``2 n``
revolutions of finite differences. The monodromy matrix's eigenvalues (Floquet multipliers) say whether the orbit is stable and
how it would lose stability: through -1 (period doubling), +1 (a fold: the jump) or as a complex pair.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Tuple

import numpy as np

from . import _core, _text
from .results import Result
from .simulation import METHOD, SolverSettings, settings_and_options, simulate


@dataclass(frozen=True)
class PeriodicOrbit:
    """The periodic steady state at the start of a revolution (t = 0, cam angle = its phase).

    ``q``, ``v``: the state (SI units per DOF) from which one revolution returns to itself within
    ``mismatch`` (displacements relative to the largest |q| on the revolution, velocities to the
    largest |v|: ``q_scale``, ``v_scale``). ``multipliers``: Floquet multipliers (complex, largest magnitude first);
    ``monodromy``: d(q, v)(T)/d(q, v)(0), ``2n x 2n``, built ``monodromy_method`` ("variational",
    "differences", or "" when none was built). ``revolutions``: what finding it cost, in
    revolutions simulated, of which ``variational_revolutions`` carried the step sensitivities. ``method``: "shooting", or "transient" when the shooting failed and the
    transient route was asked for as the fallback. ``scheme``: the solver settings the orbit belongs to
    (pass the orbit to :meth:`record` to get its time histories).
    """

    q: np.ndarray
    v: np.ndarray
    period: float
    converged: bool
    mismatch: float
    iterations: int
    monodromies: int
    revolutions: float
    multipliers: np.ndarray
    monodromy: np.ndarray
    monodromy_at_orbit: bool
    history: Tuple[float, ...]
    dof_names: Tuple[str, ...]
    q_scale: float = math.nan
    v_scale: float = math.nan
    method: str = "shooting"
    scheme: Dict[str, Any] = field(default_factory=dict)
    monodromy_method: str = ""
    variational_revolutions: float = 0.0

    def __repr__(self) -> str:  # the facts, not the state vectors and the 2n x 2n monodromy
        return (
            f"PeriodicOrbit(method={self.method!r}, converged={self.converged}, period={_text.g(self.period)} s, "
            f"mismatch={_text.g(self.mismatch, 3)}, iterations={self.iterations}, "
            f"revolutions={_text.g(self.revolutions)}, spectral_radius={_text.g(self.spectral_radius, 6)}, "
            f"{len(self.dof_names)} DOFs)"
        )

    @property
    def spectral_radius(self) -> float:
        """Largest |multiplier|: < 1 for a stable orbit (nan when no monodromy was built)."""
        return float(abs(self.multipliers[0])) if len(self.multipliers) else math.nan

    @property
    def stable(self) -> bool:
        return self.spectral_radius < 1.0

    def instability(self, margin: float = 1e-3) -> str:
        """How the orbit is (or is about to be) losing stability, from the multipliers within ``margin``
        of the unit circle or outside it: "stable", "period doubling" (a real multiplier at -1),
        "fold" (real, at +1: a jump) or "quasi-periodic" (a complex pair: chatter-like modulation)."""
        mu = self.multipliers[np.abs(self.multipliers) >= 1.0 - margin] if len(self.multipliers) else []
        if len(mu) == 0:
            return "stable"
        m = mu[0]
        if abs(m.imag) <= 1e-6 * abs(m):
            return "period doubling" if m.real < 0 else "fold"
        return "quasi-periodic"

    def record(self, system, *, revolutions: float = 1.0, decimation: int = 1, **overrides) -> Result:
        """Simulate ``revolutions`` from the orbit with the scheme it was found with (so the recorded
        revolution is the orbit itself) and return the Result."""
        return simulate(
            system,
            _settings_of(self.scheme),
            revolutions=revolutions,
            decimation=decimation,
            initial_state=(self.q, self.v),
            **overrides,
        )

    def summary(self) -> Dict[str, Any]:
        """JSON-ready facts of the orbit."""
        return {
            "method": self.method,
            "converged": self.converged,
            "mismatch": self.mismatch,
            "iterations": self.iterations,
            "monodromies": self.monodromies,
            "monodromy_method": self.monodromy_method,
            "revolutions": self.revolutions,
            "spectral_radius": self.spectral_radius,
            "instability": self.instability(),
            "multipliers": [[float(m.real), float(m.imag)] for m in self.multipliers],
        }


def periodic_steady_state(
    system,
    settings: Optional[SolverSettings] = None,
    *,
    time_step: Optional[float] = None,
    tolerance: float = 1e-9,
    max_shooting_iterations: int = 30,
    warmup_revolutions: int = 1,
    perturbation: float = 1e-6,
    multipliers: bool = True,
    monodromy: str = "auto",
    guess: Optional[PeriodicOrbit] = None,
    fallback: Optional[str] = None,
    transient_tolerance: float = 1e-6,
    transient_max_revolutions: int = 200,
    **scheme,
) -> PeriodicOrbit:
    """The periodic steady state of ``system`` (a Mechanism) by shooting on one revolution.

    ``time_step`` must divide the period (e.g. ``system.period / 4096``); the orbit is the fixed point
    of the scheme with these settings (``settings``: a :class:`SolverSettings`, or its fields as
    keywords in ``scheme``: ``method``, ``gamma``, ``beta``, ... as for :func:`camfollower.simulate`;
    ``time_step`` overrides the settings'; the solver's ``tolerance`` is the settings' field, this
    function's ``tolerance`` the shooting's), i.e. the state
    a long transient run converges to. ``tolerance``: the relative mismatch after one revolution.
    ``warmup_revolutions`` of transient first, from the system's initial state (static equilibrium)
    or from ``guess`` (a nearby orbit, e.g. the nominal case of a tolerance study: its state and
    monodromy start the iterations, which then usually need no monodromy of their own).
    ``multipliers``: build the monodromy at the converged orbit if the last one was built elsewhere
    (Floquet multipliers of the orbit itself), else keep the last one's. ``monodromy``: how it is built,
    "variational" (the scheme's step sensitivities carried through one revolution: the Newmark family
    on the dense backend), "differences" (2n revolutions of forward differences, ``perturbation``
    relative to the revolution's scales) or "auto" (variational where available; when a variational
    Newton step does not halve the mismatch, the search restarts from its first iterate by differences:
    the variational equations miss impacts within steps, e.g. a roller chattering between a groove's
    flanks).

    Raises RuntimeError with the mismatch history when the shooting does not converge (a response
    that is not periodic: contact loss with chatter, period doubling), unless ``fallback="transient"``:
    then the transient route (``simulate(settle=True)`` to ``transient_tolerance``) answers and the
    orbit says ``method="transient"`` (``converged`` False if it never settled either). A model too
    large for shooting's dense monodromy (2n > ``_core.SHOOTING_MAX_STATE_SIZE``) goes the transient
    route at once with ``fallback="transient"`` (without it: ValueError).
    """
    period = getattr(system, "period", None)
    if period is None:
        raise ValueError(
            f"periodic_steady_state needs a periodic system (with a camshaft period), got {type(system).__name__}"
        )
    if fallback not in (None, "transient"):
        raise ValueError(f"fallback must be None or 'transient', got {fallback!r}")
    if time_step is not None:
        scheme["time_step"] = time_step
    unknown = sorted(set(scheme) - set(SolverSettings.FIELDS))
    if unknown:
        raise TypeError(
            f"periodic_steady_state() got unexpected keyword argument(s) {unknown}; solver settings: "
            f"{list(SolverSettings.FIELDS)}"
        )
    settings, _ = settings_and_options(settings, None, **scheme)
    q0 = v0 = guess_monodromy = None
    if guess is not None:
        if not isinstance(guess, PeriodicOrbit):
            raise TypeError(f"guess must be a PeriodicOrbit, got {type(guess).__name__}")
        n = len(system.dof_names)
        if len(guess.q) != n:
            raise ValueError(f"guess has {len(guess.q)} DOFs, the system {n}")
        q0, v0 = guess.q, guess.v
        guess_monodromy = guess.monodromy if guess.monodromy.size else None
    if fallback == "transient" and 2 * len(system.dof_names) > _core.SHOOTING_MAX_STATE_SIZE:
        # Too large for shooting's dense monodromy (2n revolutions each): the transient route answers.
        return _transient(system, settings.fields(), None, transient_tolerance, transient_max_revolutions)
    raw = _core._shoot(
        system,
        settings,
        None,
        0.0,
        tolerance,
        max_shooting_iterations,
        warmup_revolutions,
        perturbation,
        multipliers,
        guess_monodromy,
        q0,
        v0,
        monodromy,
    )
    names = tuple(system.dof_names)
    kept = settings.fields()
    orbit = PeriodicOrbit(
        q=np.asarray(raw["q"]),
        v=np.asarray(raw["v"]),
        period=float(period),
        converged=bool(raw["converged"]),
        mismatch=float(raw["mismatch"]),
        iterations=int(raw["iterations"]),
        monodromies=int(raw["monodromies"]),
        revolutions=float(raw["revolutions"]),
        multipliers=np.asarray(raw["multipliers"], dtype=complex),
        monodromy=np.asarray(raw["monodromy"]),
        monodromy_at_orbit=bool(raw["monodromy_at_orbit"]),
        history=tuple(float(h) for h in raw["history"]),
        dof_names=names,
        q_scale=float(raw["q_scale"]),
        v_scale=float(raw["v_scale"]),
        scheme=kept,
        monodromy_method=str(raw["monodromy_method"]),
        variational_revolutions=float(raw["variational_revolutions"]),
    )
    if orbit.converged:
        return orbit
    if fallback == "transient":
        return _transient(system, kept, orbit, transient_tolerance, transient_max_revolutions)
    history = ", ".join(f"{h:.3g}" for h in orbit.history)
    raise RuntimeError(
        f"shooting did not converge to the periodic steady state in {orbit.iterations} iterations "
        f"({orbit.revolutions:g} revolutions): mismatch {orbit.mismatch:.3g} > tolerance {tolerance:g}; history "
        f"[{history}]. The response may not be periodic (contact loss with chatter, period doubling: spectral "
        f"radius {orbit.spectral_radius:.4g}); pass fallback='transient' to use the transient route instead"
    )


def _settings_of(scheme: Dict[str, Any]) -> SolverSettings:
    """The SolverSettings of an orbit's ``scheme``; an orbit pickled before the settings were one object
    carries newmark's hht_alpha = 0 and default gamma, beta, which are dropped."""
    kw = dict(scheme)
    method = kw.get("method", SolverSettings().method)
    if method != METHOD.hht and kw.get("hht_alpha") in (0, 0.0, None):
        kw.pop("hht_alpha", None)
    if method != METHOD.newmark or (kw.get("gamma"), kw.get("beta")) in ((None, None), (0.5, 0.25)):
        kw.pop("gamma", None), kw.pop("beta", None)
    return SolverSettings(**{k: v for k, v in kw.items() if v is not None})


#: Largest displacement (m, or rad) a state may hold: beyond it a run has diverged (the core's bound
#: on an initial state).
_DIVERGED = 1000.0


def _transient(
    system, scheme: Dict[str, Any], failed: Optional[PeriodicOrbit], tolerance: float, max_revolutions: int
) -> PeriodicOrbit:
    """The state a settled transient run reaches (``failed``: the shooting that did not converge, or
    None when none was tried)."""
    r = simulate(
        system,
        revolutions=1,
        record_last_revolutions=1,
        settle=True,
        settle_tolerance=tolerance,
        settle_max_revolutions=max_revolutions,
        settle_dofs=list(system.dof_names),
        **_settings_of(scheme).fields(),
    )
    settle = r.settle or {}
    q, v = np.array(r.q[-1]), np.array(r.v[-1])
    if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v)) and np.max(np.abs(q), initial=0.0) <= _DIVERGED):
        # A state no mechanism reaches (the core refuses it as a start): the scheme diverged at this
        # step, typically impacts after a contact loss integrated with a step far too coarse for them.
        raise RuntimeError(
            f"the transient route diverged at time_step = {_settings_of(scheme).time_step:.6g} s: after "
            f"{settle.get('revolutions', 0):g} revolutions max |q| = {np.max(np.abs(q)):.3g} (m or rad); the step "
            "is too coarse for this response (contact loss with impacts): use a finer step or an accuracy"
        )
    return PeriodicOrbit(
        q=q,
        v=v,
        period=float(system.period),
        converged=bool(settle.get("settled", False)),
        mismatch=float(settle.get("change", math.nan)),
        iterations=0,
        monodromies=0,
        revolutions=(failed.revolutions if failed else 0.0) + float(settle.get("revolutions", 0)) + 1.0,
        multipliers=np.zeros(0, dtype=complex),
        monodromy=np.zeros((0, 0)),
        monodromy_at_orbit=False,
        history=tuple(settle.get("history", ())),
        dof_names=tuple(system.dof_names),
        q_scale=failed.q_scale if failed else max(float(np.max(np.abs(r.q))), 1e-9),
        v_scale=failed.v_scale if failed else max(float(np.max(np.abs(r.v))), 1e-9),
        method="transient",
        scheme=scheme,
    )


__all__ = ["PeriodicOrbit", "periodic_steady_state"]
