# SPDX-License-Identifier: BSD-3-Clause
"""Monte-Carlo tolerance studies: what a design's tolerances cost in contact margin, accelerations and
residual vibration.

Each toleranced parameter gets a distribution of its deviation from the nominal value
(:class:`Normal`, :class:`Uniform`, :class:`TruncatedNormal`; absolute in SI units, or ``relative``
to the nominal). Case ``i`` of a study with seed ``s`` draws its values from
``numpy.random.default_rng([s, i])``: any case can be rerun alone, and a study's cases do not depend on
how many there are or on which executor ran them. Every case is solved for its periodic steady state
by shooting from its own static equilibrium (about 18 revolutions per case for the paper's mechanism;
starting from the nominal orbit does not save revolutions: a few micrometres of eccentricity move the
orbit by more than the contact deflection).

A model is described by a picklable builder, ``build(values: dict) -> Mechanism`` with
``build.nominal(name)``: :class:`PaperCase` (the paper's mechanism: every ``Parameters`` name, the cam's
``eccentricity`` and a profile ``waviness`` amplitude, the guide clearance, the damping ratio) or
:class:`ConfigCase` (any numeric value of a config file by its key path, e.g.
``"contact.0.follower.offset"`` or ``"preset.parameters.contact_stiffness"``).

Out-of-range values are refused before anything runs: the model is built at each bounded
distribution's ends (for a normal distribution at +-4 standard deviations); a bound the model rejects
stops the study with the model's message naming the parameter (use a TruncatedNormal to stay inside
a valid range). Results: :class:`MonteCarloResult` (rows, a pandas DataFrame, Parquet, summary
statistics, sensitivities, plots).
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from . import _core, _text
from .executors import check_executor, run_cases
from .response import STUDY_STEPS_PER_REVOLUTION, steady_response

#: Metrics of each case kept in the table (from camfollower.response.steady_response).
METRICS = ("min_force_N", "min_force_angle_deg", "max_force_N", "contact_lost", "lost_fraction",
           "max_abs_acceleration", "dwell_residual", "converged", "revolutions", "iterations")


def _finite(name: str, v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ValueError(f"{name} must be a finite number, got {_echo(v)}")
    return float(v)


def _flag(name: str, v) -> None:
    # `relative = "no"` would be truthy: a flag is a bool or nothing.
    if not isinstance(v, bool):
        raise ValueError(f"{name} must be True or False, got {_echo(v)}")


def _echo(v) -> str:
    text = "".join(c if c.isprintable() else "?" for c in repr(v))
    return text if len(text) <= 60 else text[:60] + "..."


@dataclass(frozen=True)
class Normal:
    """Deviation ~ N(mean, std^2); ``relative``: as a fraction of the nominal value."""

    std: float
    mean: float = 0.0
    relative: bool = False

    def __post_init__(self):
        if _finite("Normal std", self.std) < 0:
            raise ValueError(f"Normal std must be >= 0 (a spread), got {self.std}")
        _finite("Normal mean", self.mean)
        _flag("Normal relative", self.relative)

    def sample(self, rng) -> float:
        return self.mean + self.std * rng.standard_normal()

    def extremes(self) -> Tuple[float, float]:
        return self.mean - 4 * self.std, self.mean + 4 * self.std


@dataclass(frozen=True)
class Uniform:
    """Deviation ~ U(low, high); ``relative``: as a fraction of the nominal value."""

    low: float
    high: float
    relative: bool = False

    def __post_init__(self):
        if _finite("Uniform high", self.high) < _finite("Uniform low", self.low):
            raise ValueError(f"Uniform needs low <= high (a non-negative spread), got low {self.low}, high {self.high}")
        _flag("Uniform relative", self.relative)

    def sample(self, rng) -> float:
        return self.low + (self.high - self.low) * rng.random()

    def extremes(self) -> Tuple[float, float]:
        return self.low, self.high


@dataclass(frozen=True)
class TruncatedNormal:
    """Deviation ~ N(mean, std^2) restricted to [low, high] (redrawn until inside); ``relative``: as a
    fraction of the nominal value. The interval must hold at least 1e-3 of the probability."""

    std: float
    low: float
    high: float
    mean: float = 0.0
    relative: bool = False

    def __post_init__(self):
        if _finite("TruncatedNormal std", self.std) <= 0:
            raise ValueError(f"TruncatedNormal std must be > 0, got {self.std}")
        if _finite("TruncatedNormal high", self.high) <= _finite("TruncatedNormal low", self.low):
            raise ValueError(f"TruncatedNormal needs low < high, got low {self.low}, high {self.high}")
        _finite("TruncatedNormal mean", self.mean)
        _flag("TruncatedNormal relative", self.relative)
        cdf = lambda x: 0.5 * (1 + math.erf((x - self.mean) / (self.std * math.sqrt(2))))  # noqa: E731
        if cdf(self.high) - cdf(self.low) < 1e-3:
            raise ValueError(f"TruncatedNormal [{self.low}, {self.high}] holds less than 1e-3 of N({self.mean}, "
                             f"{self.std}^2): widen the interval or move the mean")

    def sample(self, rng) -> float:
        while True:
            x = self.mean + self.std * rng.standard_normal()
            if self.low <= x <= self.high:
                return x

    def extremes(self) -> Tuple[float, float]:
        return self.low, self.high


DISTRIBUTIONS = {"normal": Normal, "uniform": Uniform, "truncated_normal": TruncatedNormal}


def distribution(spec: Mapping[str, Any]):
    """A distribution from a dict (config files): {"distribution": "normal", "std": ..., ...}."""
    spec = dict(spec)
    kind = spec.pop("distribution", None)
    if not isinstance(kind, str) or kind not in DISTRIBUTIONS:  # a dict or list is unhashable: no `in` first
        raise ValueError(f"distribution must be one of {list(DISTRIBUTIONS)}, got {_echo(kind)}")
    cls = DISTRIBUTIONS[kind]
    fields = [f.name for f in dataclasses.fields(cls)]
    for key in spec:
        if key not in fields:
            raise ValueError(f"{kind} distribution: unknown key {_echo(key)}; known: {', '.join(fields)}")
    for f in dataclasses.fields(cls):
        if f.name not in spec and f.default is dataclasses.MISSING:
            raise ValueError(f"{kind} distribution: the key {f.name!r} is required")
    return cls(**spec)


class PaperCase:
    """Builder of the paper's mechanism (presets.paper) from named values: every ``Parameters`` name,
    ``eccentricity`` (m, the cam centre's offset; exact geometry), ``waviness`` (m, amplitude of a
    profile error of ``waviness_order`` waves per revolution), ``guide_clearance`` (m, radial) and
    ``element_damping_ratio``. ``fixed`` values apply to every case (e.g. camshaft_speed_rpm)."""

    EXTRA = {"eccentricity": 0.0, "waviness": 0.0, "guide_clearance": 0.0, "element_damping_ratio": 0.0}

    def __init__(self, waviness_order: int = 10, **fixed):
        self.waviness_order = int(waviness_order)
        self.fixed = dict(fixed)
        for k in self.fixed:
            self._check(k)

    def _check(self, name: str) -> None:
        if name not in self.EXTRA and name not in _core.Parameters.names():
            raise ValueError(f"PaperCase: unknown parameter {name!r}; known: {_core.Parameters.names() + list(self.EXTRA)}")

    def nominal(self, name: str) -> float:
        self._check(name)
        if name == "contact_damping":
            raise ValueError("PaperCase: contact_damping is a model choice, not a number to scatter; "
                             "fix it with PaperCase(contact_damping=...)")
        if name in self.fixed:
            return float(self.fixed[name])
        return self.EXTRA[name] if name in self.EXTRA else _core.Parameters().get(name)

    def __call__(self, values: Mapping[str, float]):
        from . import presets

        v = {**self.fixed, **values}
        extra = {k: v.pop(k) for k in list(v) if k in self.EXTRA}
        program = _core.MotionProgram.paper_default()
        if extra.get("waviness", 0.0):
            program = program.with_profile_error(_core.ProfileError.waviness(extra["waviness"], self.waviness_order))
        ecc = _core.CamEccentricity(extra["eccentricity"]) if extra.get("eccentricity", 0.0) else None
        return presets.paper(_core.Parameters(**v), program, eccentricity=ecc,
                             guide_clearance=extra.get("guide_clearance", 0.0),
                             element_damping_ratio=extra.get("element_damping_ratio", 0.0))

    def __repr__(self) -> str:
        fixed = "".join(f", {k}={_text.g(v)}" for k, v in self.fixed.items())
        return f"PaperCase(waviness_order={self.waviness_order}{fixed})"


class ConfigCase:
    """Builder of a config file's mechanism with values replaced by key path: "a.b.0.c" is
    ``data["a"]["b"][0]["c"]`` (lists by index). The nominal value must be a plain number (SI) in
    the config."""

    def __init__(self, data: Mapping[str, Any], base_dir: os.PathLike | str = "."):
        self.data = copy.deepcopy(dict(data))
        self.base_dir = os.fspath(base_dir)

    @classmethod
    def from_file(cls, path: os.PathLike | str) -> "ConfigCase":
        from .config import load_config

        case = load_config(path)
        return cls(case.data, os.path.dirname(os.path.abspath(os.fspath(path))))

    def _slot(self, data, path: str):
        parts = path.split(".")
        node = data
        for i, p in enumerate(parts[:-1]):
            try:
                node = node[int(p)] if isinstance(node, list) else node[p]
            except (KeyError, IndexError, ValueError, TypeError):
                raise ValueError(f"parameter {path!r}: no {'.'.join(parts[:i + 1])!r} in the config") from None
        last = parts[-1]
        if isinstance(node, list):
            try:
                last = int(last)
                node[last]
            except (ValueError, IndexError):
                raise ValueError(f"parameter {path!r}: no element {parts[-1]!r} in the config's list") from None
        elif not isinstance(node, dict) or last not in node:
            raise ValueError(f"parameter {path!r}: the config has no such value (give its nominal value in the file)")
        return node, last

    def nominal(self, name: str) -> float:
        node, key = self._slot(self.data, name)
        v = node[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"parameter {name!r}: its nominal value {v!r} must be a plain number in SI units to be toleranced")
        return float(v)

    def __call__(self, values: Mapping[str, float]):
        from .config import config_from_dict

        data = copy.deepcopy(self.data)
        for name, value in values.items():
            node, key = self._slot(data, name)
            node[key] = float(value)
        return config_from_dict(data, self.base_dir).mechanism


def _draw(tolerances: Mapping[str, Any], nominal: Mapping[str, float], seed: int, case: int) -> Dict[str, float]:
    rng = np.random.default_rng([seed, case])
    out = {}
    for name, dist in tolerances.items():
        d = dist.sample(rng)
        out[name] = nominal[name] * (1.0 + d) if dist.relative else nominal[name] + d
    return out


def _mc_case(build, options: Dict[str, Any], values: Dict[str, float]) -> Dict[str, Any]:
    row = steady_response(build(values), **options)
    return {k: row[k] for k in METRICS}


@dataclass
class MonteCarloResult:
    """A Monte-Carlo study's outcome: ``rows`` (one dict per case: ``case``, ``seed``, the parameter
    values, the metrics, ``ok`` and ``error``), the ``nominal`` case's row, the toleranced
    ``parameters`` and the ``metrics``."""

    rows: List[Dict[str, Any]]
    nominal: Dict[str, Any]
    parameters: List[str]
    metrics: List[str] = field(default_factory=lambda: list(METRICS))
    seed: int = 0

    @property
    def table(self):
        """The rows as a pandas DataFrame (optional extra: pip install 'camfollower[study]')."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("MonteCarloResult.table needs pandas: pip install 'camfollower[study]'") from None
        return pd.DataFrame(self.rows)

    def failed(self) -> List[Dict[str, Any]]:
        return [r for r in self.rows if not r["ok"]]

    def __repr__(self) -> str:  # a line, not every row
        ok = [r for r in self.rows if r["ok"]]
        lost = sum(bool(r.get("contact_lost")) for r in ok)
        forces = [r["min_force_N"] for r in ok if isinstance(r.get("min_force_N"), float) and math.isfinite(r["min_force_N"])]
        spread = (f", min_force_N {_text.g(min(forces), 4)} to {_text.g(max(forces), 4)}" if forces else "")
        return (f"MonteCarloResult({len(self.rows)} cases, {len(self.rows) - len(ok)} failed, {lost} lost contact"
                f"{spread}; seed {self.seed}; parameters: {', '.join(self.parameters)})")

    def _matrix(self, names: Sequence[str]) -> np.ndarray:
        ok = [r for r in self.rows if r["ok"]]
        return np.array([[float(r[n]) for n in names] for r in ok], dtype=float).reshape(len(ok), len(names))

    def summary(self) -> Dict[str, Any]:
        """Per metric: mean, std, min, 5/50/95 % percentiles, max and the nominal value; counts of cases,
        failures and cases that lost contact."""
        numeric = [m for m in self.metrics if m not in ("converged", "contact_lost")]
        X = self._matrix(numeric)
        out: Dict[str, Any] = {"cases": len(self.rows), "failed": len(self.failed()),
                               "contact_lost": int(sum(bool(r.get("contact_lost")) for r in self.rows if r["ok"])),
                               "seed": self.seed, "metrics": {}}
        for j, m in enumerate(numeric):
            x = X[:, j] if X.size else np.zeros(0)
            x = x[np.isfinite(x)]
            if x.size == 0:
                continue
            p5, p50, p95 = np.percentile(x, [5, 50, 95])
            out["metrics"][m] = {"mean": float(x.mean()), "std": float(x.std(ddof=1)) if x.size > 1 else 0.0,
                                 "min": float(x.min()), "p5": float(p5), "p50": float(p50), "p95": float(p95),
                                 "max": float(x.max()), "nominal": float(self.nominal[m])}
        return out

    def sensitivities(self, metric: str = "min_force_N") -> List[Dict[str, Any]]:
        """How each parameter drives ``metric``: Pearson correlation and the standardized regression
        coefficient (linear least squares on the standardized values: the metric's change in standard
        deviations per standard deviation of the parameter), strongest first."""
        if metric not in self.metrics:
            raise ValueError(f"metric must be one of {self.metrics}, got {metric!r}")
        X = self._matrix(list(self.parameters) + [metric])
        X = X[np.all(np.isfinite(X), axis=1)]
        if X.shape[0] < len(self.parameters) + 2:
            raise ValueError(f"sensitivities need at least {len(self.parameters) + 2} successful cases, got {X.shape[0]}")
        sd = X.std(axis=0, ddof=1)
        Z = np.divide(X - X.mean(axis=0), sd, out=np.zeros_like(X), where=sd > 0)
        coef = np.linalg.lstsq(Z[:, :-1], Z[:, -1], rcond=None)[0]
        out = []
        for j, p in enumerate(self.parameters):
            r = float(np.corrcoef(X[:, j], X[:, -1])[0, 1]) if sd[j] > 0 and sd[-1] > 0 else 0.0
            out.append({"parameter": p, "correlation": r, "standardized_coefficient": float(coef[j])})
        return sorted(out, key=lambda d: -abs(d["standardized_coefficient"]))

    def to_parquet(self, path: os.PathLike | str, *, protect=()) -> None:
        """Write the table as Parquet (pyarrow), atomically (camfollower._files; never over `protect`)."""
        import io

        from . import _files

        buf = io.BytesIO()
        self.table.to_parquet(buf, index=False)
        _files.write_bytes(path, buf.getvalue(), protect=protect)

    def plot(self, metric: str = "min_force_N"):
        """Histogram of ``metric`` (nominal marked) and its scatter against the most influential
        parameter. Returns the figure."""
        import matplotlib.pyplot as plt

        fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
        x = self._matrix([metric])[:, 0]
        a.hist(x[np.isfinite(x)], bins=max(10, int(math.sqrt(max(len(x), 1)))), color="tab:blue", alpha=0.8)
        a.axvline(self.nominal[metric], color="tab:red", label="nominal")
        a.set_xlabel(metric)
        a.set_ylabel("cases")
        a.legend()
        top = self.sensitivities(metric)[0]["parameter"]
        X = self._matrix([top, metric])
        b.plot(X[:, 0], X[:, 1], ".", ms=3)
        b.set_xlabel(top)
        b.set_ylabel(metric)
        b.set_title(f"most influential: {top}")
        fig.tight_layout()
        return fig


def _check_ranges(build, tolerances, nominal) -> None:
    for name, dist in tolerances.items():
        for end in dist.extremes():
            value = nominal[name] * (1.0 + end) if dist.relative else nominal[name] + end
            try:
                build({name: value})
            except ValueError as e:
                kind = type(dist).__name__
                raise ValueError(f"tolerance on {name!r}: the {kind} reaches {value:.6g} (nominal {nominal[name]:.6g}), "
                                 f"which the model refuses: {e}. Narrow it or use a TruncatedNormal inside the valid "
                                 "range") from None


def monte_carlo(build: Callable[[Mapping[str, float]], Any], tolerances: Mapping[str, Any], *, cases: int = 100,
                seed: int = 0, contact: Optional[str] = None, steps_per_revolution: int = STUDY_STEPS_PER_REVOLUTION,
                executor=None, workers: Optional[int] = None, progress: bool = True) -> MonteCarloResult:
    """``cases`` random variants of the model ``build`` describes (module docstring), each solved to
    its periodic steady state and measured (:data:`METRICS`), on ``executor`` (camfollower.executors).

    ``tolerances``: {parameter: Normal | Uniform | TruncatedNormal}. The nominal model is solved first
    first (its row is ``nominal``). A case that fails (non-periodic response after the transient
    fallback, a model error, a crashed worker) is kept as a row with ``ok`` False, its values, seed and
    the error.
    """
    if not tolerances:
        raise ValueError("tolerances: give at least one {parameter: distribution}")
    for name, d in tolerances.items():
        if not isinstance(d, (Normal, Uniform, TruncatedNormal)):
            raise TypeError(f"tolerance on {name!r} must be a Normal, Uniform or TruncatedNormal, got {type(d).__name__}")
    if isinstance(cases, bool) or not isinstance(cases, int) or not 1 <= cases <= 10_000_000:
        raise ValueError(f"cases must be an integer in [1, 1e7], got {cases!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    check_executor(executor, workers)  # before the nominal model is solved
    nominal = {name: build.nominal(name) for name in tolerances}
    _check_ranges(build, tolerances, nominal)
    options = dict(contact=contact, steps_per_revolution=steps_per_revolution, fallback="transient", multipliers=False)
    nominal_row = steady_response(build({}), contact=contact, steps_per_revolution=steps_per_revolution,
                                  fallback="transient")
    values = [_draw(tolerances, nominal, seed, i) for i in range(cases)]
    fn = functools.partial(_mc_case, build, options)
    outcomes = run_cases(fn, values, executor=executor, workers=workers, progress=progress, desc="Monte-Carlo")
    rows = []
    for i, (o, v) in enumerate(zip(outcomes, values)):
        row = {"case": i, "seed": seed, **v}
        if o.ok:
            row.update(o.value, ok=True, error="")
        else:
            row.update({m: math.nan for m in METRICS}, ok=False, error=o.error)
        rows.append(row)
    return MonteCarloResult(rows=rows, nominal={k: nominal_row[k] for k in METRICS}, parameters=list(tolerances),
                            seed=seed)


__all__ = ["ConfigCase", "DISTRIBUTIONS", "METRICS", "MonteCarloResult", "Normal", "PaperCase", "TruncatedNormal",
           "Uniform", "distribution", "monte_carlo"]
