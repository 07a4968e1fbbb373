"""Ready-made mechanisms, built from the same parts as any user mechanism."""

from __future__ import annotations

from typing import Optional

from ._core import CamEccentricity, Mechanism, MotionProgram, Parameters, paper_preset, realistic_damping_ratio

#: Modal damping ratio of :func:`paper_damped` (machine structures: 2-5 % of critical; defined in C++).
REALISTIC_DAMPING_RATIO: float = realistic_damping_ratio


def paper(parameters: Optional[Parameters] = None, program: Optional[MotionProgram] = None, *,
          eccentricity: Optional[CamEccentricity] = None, guide_clearance: float = 0.0,
          guide_wall_damping_factor: float = 0.0, guide_friction: float = 0.0,
          modal_damping_ratio: float = 0.0) -> Mechanism:
    """The paper's 7-DOF cam-follower model (Tounsi et al.): camshaft on bearings (y1, x1), roller on
    its pin (y2, x2), follower rod in its guide (y3, x3), follower top on the preloaded return spring
    (y4); one contact named "cam" between a disk cam and the offset translating roller. ``parameters``
    as for CamFollowerModel (Table 2 defaults), ``program`` the cam's lift (Table 1 default).

    Defects, from their mechanisms: ``eccentricity`` (a CamEccentricity: the cam's centre displaced,
    exact, or the paper's literal force as a named formulation); ``guide_clearance`` (m, radial) > 0
    puts the rod x3 in a gap whose walls have the guide stiffness K_rb (clearance "guide", wall damping
    factor ``guide_wall_damping_factor`` in s/m, Coulomb ``guide_friction`` on the rod's sliding y3).
    ``modal_damping_ratio`` in (0, 1) damps every mode at that ratio in place of the paper's element
    dampers (which leave the lateral modes at ~1e-5 of critical). The return spring's preload is
    calibrated on the healthy mechanism, so every variant has the same spring."""
    return paper_preset(parameters, program, eccentricity=eccentricity, guide_clearance=guide_clearance,
                        guide_wall_damping_factor=guide_wall_damping_factor, guide_friction=guide_friction,
                        modal_damping_ratio=modal_damping_ratio)


def paper_damped(parameters: Optional[Parameters] = None, program: Optional[MotionProgram] = None, *,
                 damping_ratio: float = REALISTIC_DAMPING_RATIO, **options) -> Mechanism:
    """The paper's mechanism with realistic damping: every mode at ``damping_ratio`` of critical
    (default 3 %), about the static equilibrium at theta = 0. Other options as for :func:`paper`."""
    return paper(parameters, program, modal_damping_ratio=damping_ratio, **options)


__all__ = ["paper", "paper_damped", "REALISTIC_DAMPING_RATIO"]
