# SPDX-License-Identifier: BSD-3-Clause
"""camfollower: dynamics of flexible cam-follower mechanisms.

SI units throughout (m, kg, s, N, rad). The compiled core lives in ``camfollower._core``; this
package re-exports it and adds the Python-side analysis and the paper study.

>>> import camfollower as cf
>>> roller = cf.TranslatingRoller(base_radius=0.030, roller_radius=0.008, offset=0.010)  # the paper's
>>> c = roller.contact(cf.MotionProgram.paper_default(), theta=0.1)     # on the base circle
>>> round(c["pressure_angle"], 6)            # atan(-e / s0), rad
-0.266294
"""

import numpy as _numpy  # noqa: F401  (imported here, not lazily inside the first simulate call)

from . import _api_errors, _core

_api_errors.install(_core)  # argument mismatches: short TypeErrors naming the call, not pybind11's dumps
from . import ecam, export, motion, presets, synthesis
from ._core import (  # noqa: E402
    ArmTurn,
    BarrelArmRoller,
    BarrelRoller,
    BoundaryContinuity,
    CamEccentricity,
    ContinuityReport,
    CouplerLinkage,
    Elastic,
    Groove,
    LineContact,
    Mechanism,
    MechanismBuilder,
    MotionLaw,
    MotionProgram,
    OscillatingFlat,
    OscillatingRoller,
    Parameters,
    PeakCoefficients,
    ProfileError,
    Segment,
    SpeedModulation,
    SpeedProgram,
    SpeedRamp,
    TranslatingFlat,
    TranslatingRoller,
)
from .config import Config, config_from_dict, load_config
from .periodic import PeriodicOrbit, periodic_steady_state
from .results import Result
from .simulation import RunOptions, SolverSettings, settings_and_options, simulate, simulate_many

#: The integration methods by name (the ``method`` of simulate and the config's ``scheme``), in the
#: order they are listed, each with its global order (0: "auto", the chosen method's) and a summary.
METHODS = {name: {"order": order, "summary": summary} for name, (order, summary) in _core.METHODS.items()}

__all__ = [
    "METHODS",
    "ArmTurn",
    "BarrelArmRoller",
    "BarrelRoller",
    "BoundaryContinuity",
    "CamEccentricity",
    "Config",
    "ContinuityReport",
    "CouplerLinkage",
    "Elastic",
    "Groove",
    "LineContact",
    "Mechanism",
    "MechanismBuilder",
    "MotionLaw",
    "MotionProgram",
    "SpeedModulation",
    "SpeedProgram",
    "SpeedRamp",
    "OscillatingFlat",
    "OscillatingRoller",
    "Parameters",
    "PeakCoefficients",
    "PeriodicOrbit",
    "ProfileError",
    "Result",
    "RunOptions",
    "Segment",
    "SolverSettings",
    "TranslatingFlat",
    "TranslatingRoller",
    "config_from_dict",
    "ecam",
    "export",
    "load_config",
    "motion",
    "periodic_steady_state",
    "presets",
    "simulate",
    "settings_and_options",
    "simulate_many",
    "synthesis",
]
__version__ = _core.__version__  # stated once, in pyproject.toml
