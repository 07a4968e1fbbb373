# SPDX-License-Identifier: BSD-3-Clause
"""What the lift synthesis measures on the flexible mechanism: one periodic steady state per speed,
reduced to the samples the objective squares (or bounds) and the contact margin.

Every evaluation is a normal periodic steady state (camfollower.periodic) of the mechanism with the
candidate program in the contact, at a fixed step the accuracy search chose for the start lift. The
samples are linear in the lift for a linear mechanism, nearly so with Hertz contacts; the optimizer
(camfollower.synthesis) relies on that for its Gauss-Newton model.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from .periodic import PeriodicOrbit, periodic_steady_state
from .response import _dwells, contact_of, scheme_settings, study_scheme

#: What the objective measures on the output DOF (docs/synthesis.md).
OBJECTIVES = {
    "residual": "residual vibration in the dwells: the output less its quasi-static path (m or rad)",
    "follower_error": "the output less its quasi-static path over the whole revolution (m or rad)",
    "acceleration": "the output's acceleration over the whole revolution (m/s^2 or rad/s^2)",
}
MEASURES = ("rms", "peak")
#: Samples per revolution the objective keeps (rms; a peak keeps fewer, each a constraint).
RMS_SAMPLES, PEAK_SAMPLES = 4096, 512
#: Samples of the output's acceleration a limit on it constrains, per revolution.
ACCELERATION_SAMPLES = 1024
#: Shooting tolerance (relative mismatch after a revolution): the residuals the synthesis reaches are
#: ~1e-9 of the lift, and the finite differences need them well below that (rounding: ~1e-11).
SHOOTING_TOLERANCE = 3e-11


def with_program(system, contact: str, program):
    """``system`` with ``program`` in the contact ``contact`` (everything else as it is)."""
    state = system.__getstate__()
    for c in state["contacts"]:
        if c["name"] == contact:
            c["program"] = program
    out = type(system).__new__(type(system))
    out.__setstate__(state)
    return out


@dataclass
class Sample:
    """One periodic steady state, reduced."""

    values: np.ndarray  # the objective's samples
    min_force: float  # N (nan for a grooved contact)
    peak_acceleration: float  # the output's largest |acceleration| over the revolution
    acceleration: np.ndarray  # the output's acceleration, every ACCELERATION_SAMPLES-th of a revolution
    orbit: PeriodicOrbit
    revolutions: float
    stress: Optional[np.ndarray] = None  # Hertz pressure (Pa) at the same samples, with a line contact


def check_objective(system, contact: Optional[str], output: Optional[str], objective: str, measure: str):
    """(the contact's description, the output DOF), or ValueError naming what does not exist."""
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {sorted(OBJECTIVES)}, got {objective!r}")
    if measure not in MEASURES:
        raise ValueError(f"measure must be one of {list(MEASURES)}, got {measure!r}")
    c = contact_of(system, contact)
    names = list(system.dof_names)
    dof = c["dof"] if output is None else output
    if dof not in names:
        raise ValueError(f"output: unknown DOF {dof!r}; the mechanism's DOFs are {names}")
    if objective == "residual" and not any(_dwells(c["program"])):
        raise ValueError(
            f"objective 'residual' measures the dwells, and contact {c['name']!r}'s program has none; choose "
            "'follower_error' or 'acceleration'"
        )
    return c, dof


class Dynamics:
    """Evaluates a candidate program at each speed of the band."""

    def __init__(
        self,
        system,
        contact: Optional[str],
        output: Optional[str],
        objective: str,
        measure: str,
        speeds,
        steps,
        line_contact=None,
    ):
        self.contact, self.output = check_objective(system, contact, output, objective, measure)
        self.system = system
        self.line_contact = line_contact
        self.follower = next(c["follower"] for c in system.builder().contacts if c["name"] == self.contact["name"])
        self.objective, self.measure = objective, measure
        self.speeds = [float(s) for s in speeds]
        self.steps = int(steps)
        self.schemes = [
            scheme_settings(study_scheme(system.with_camshaft_speed_rpm(s), self.steps)) for s in self.speeds
        ]
        keep = RMS_SAMPLES if measure == "rms" else PEAK_SAMPLES
        self.decimation = max(1, self.steps // keep)
        self.evaluations = 0
        self.revolutions = 0.0
        self._count = threading.Lock()  # runs come from several threads

    def run(self, program, index: int, guess: Optional[PeriodicOrbit] = None, multipliers: bool = False) -> Sample:
        """The steady state at speed ``index`` with ``program``; RuntimeError if it is not periodic."""
        speed = self.speeds[index]
        system = with_program(self.system, self.contact["name"], program).with_camshaft_speed_rpm(speed)
        orbit = periodic_steady_state(
            system,
            time_step=system.period / self.steps,
            **self.schemes[index],
            guess=guess,
            multipliers=multipliers,
            warmup_revolutions=0 if guess is not None else 1,
            tolerance=SHOOTING_TOLERANCE,
        )
        record = orbit.record(system, decimation=self.decimation)
        name, dof = self.contact["name"], self.output
        acceleration = np.asarray(record[f"a.{dof}"])[1:]
        # The reduction is the library's (synthesis/lift_samples.hpp), in the reference program's dwells.
        reduced = _core._lift_samples(
            system,
            name,
            dof,
            self.objective,
            np.asarray(record["theta"])[1:],
            np.asarray(record[f"q.{dof}"])[1:],
            acceleration,
            np.asarray(record[f"{name}.force"])[1:],
            self.contact["program"],
        )
        values, force = np.asarray(reduced["values"]), float(reduced["min_force"])
        with self._count:
            self.evaluations += 1
            self.revolutions += orbit.revolutions + 1.0
        peak = float(reduced["peak_acceleration"])
        stride = max(1, len(acceleration) // ACCELERATION_SAMPLES)
        stress = None
        if self.line_contact is not None:
            # The Hertz pressure of the contact force at the cam angle where it acts, without contact: 0.
            forces = np.maximum(np.asarray(record[f"{name}.force"])[1:][::stride], 0.0)
            cam = np.mod(np.asarray(record[f"{name}.cam_angle"])[1:][::stride], 2.0 * math.pi)
            stress = np.asarray(self.line_contact.profile_stress(self.follower, program, forces, cam)["max_pressure"])
        return Sample(values, force, peak, acceleration[::stride], orbit, orbit.revolutions + 1.0, stress)

    def measure_of(self, values: np.ndarray) -> float:
        """The objective's measure of one speed's samples (rms or peak |.|)."""
        if self.measure == "rms":
            return float(np.sqrt(np.mean(values**2)))
        return float(np.max(np.abs(values)))
