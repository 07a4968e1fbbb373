# SPDX-License-Identifier: BSD-3-Clause
"""Ready-made mechanisms, built from the same parts as any user mechanism."""

from __future__ import annotations

from typing import Optional

from ._core import (
    CamEccentricity,
    Mechanism,
    MotionProgram,
    Parameters,
    paper_preset,
    realistic_damping_ratio,
    valve_train_parameter_units,
    valve_train_preset,
)

#: Element damping ratio of :func:`paper_damped` (machine structures: 2-5 % of critical; defined in C++).
REALISTIC_DAMPING_RATIO: float = realistic_damping_ratio


def paper(
    parameters: Optional[Parameters] = None,
    program: Optional[MotionProgram] = None,
    *,
    eccentricity: Optional[CamEccentricity] = None,
    guide_clearance: float = 0.0,
    guide_wall_damping_factor: float = 0.0,
    guide_friction: float = 0.0,
    element_damping_ratio: float = 0.0,
    paper_backlash: float = 0.0,
    paper_backlash_switch_width: float = 0.0,
) -> Mechanism:
    """The paper's 7-DOF cam-follower model (Tounsi et al.): camshaft on bearings (y1, x1), roller on
    its pin (y2, x2), follower rod in its guide (y3, x3), follower top on the preloaded return spring
    (y4); one contact named "cam" between a disk cam and the offset translating roller. ``parameters``
    a :class:`Parameters` card (Table 2 defaults), ``program`` the cam's lift (Table 1 default).

    The defects, from their mechanisms: ``eccentricity`` (a CamEccentricity: the cam's centre displaced,
    exact, or the paper's literal force as a named formulation); ``guide_clearance`` (m, radial) > 0
    puts the rod x3 in a gap whose walls have the guide stiffness K_rb (clearance "guide", wall damping
    factor ``guide_wall_damping_factor`` in s/m, Coulomb ``guide_friction`` on the rod's sliding y3).
    ``element_damping_ratio`` in (0, 1) puts a damper on every element in place of the paper's few
    (which leave the lateral modes at ~1e-5 of critical): each spring k between masses m_a, m_b gets
    c = 2 zeta sqrt(k m_a m_b / (m_a + m_b)); the cam contact and the guide walls the same through their
    Hunt-Crossley factor at the return spring's force on the dwell. Only element deformation rates are
    damped, so the follower's lift is not resisted. The return spring's preload is calibrated on the
    healthy mechanism, so every variant has the same spring.

    The paper's literal reading of the guide clearance, a named formulation beside ``guide_clearance``:
    ``paper_backlash`` (m) > 0 imposes the rod's side from the program (its eqs 12-18): offset e + b
    during rises and e - b during returns, dwells keeping the last side, the switch ramped over
    ``paper_backlash_switch_width`` (rad; 0: the literal hard switch); the contact geometry follows the
    offset and the guide spring K_rb is anchored on the displaced rod."""
    return paper_preset(
        parameters,
        program,
        eccentricity=eccentricity,
        guide_clearance=guide_clearance,
        guide_wall_damping_factor=guide_wall_damping_factor,
        guide_friction=guide_friction,
        element_damping_ratio=element_damping_ratio,
        paper_backlash=paper_backlash,
        paper_backlash_switch_width=paper_backlash_switch_width,
    )


def paper_damped(
    parameters: Optional[Parameters] = None,
    program: Optional[MotionProgram] = None,
    *,
    damping_ratio: float = REALISTIC_DAMPING_RATIO,
    **options,
) -> Mechanism:
    """The paper's mechanism with realistic damping: every element at ``damping_ratio`` of its own
    critical damping (default 3 %; the modes then have 2-5 %). Other options as for :func:`paper`."""
    return paper(parameters, program, element_damping_ratio=damping_ratio, **options)


def valve_train(engine_speed_rpm: float = 4000.0, **parameters) -> Mechanism:
    """An inline engine's camshaft: one flexible, twisting hollow shaft on radial bearings between the
    cylinders, driven at x = 0 through the timing drive's torsional compliance, with
    ``valves_per_cylinder`` cams per cylinder phased by ``firing_order``; each cam lifts a roller
    tappet and valve (one mass, DOF "c<cyl>v<valve>.valve") against a valve spring that surges (a
    chain of masses "c<cyl>v<valve>.spring.<k>"). The camshaft turns at half ``engine_speed_rpm``.

    Defaults: a four-cylinder, four-valve head's intake camshaft (8 cams, firing order 1-3-4-2, 9 mm
    lift). ``parameters``: ``cylinders``, ``valves_per_cylinder`` (1 or 2), ``spring_elements``,
    ``firing_order`` and every real parameter of :data:`VALVE_TRAIN_PARAMETERS` (SI units). Contacts
    are named "c<cyl>v<valve>"; the shaft "camshaft", bearings "bearing<k>", the drive "drive"."""
    return valve_train_preset(float(engine_speed_rpm), parameters)


#: The valve-train preset's real-valued parameters and their SI units.
VALVE_TRAIN_PARAMETERS: dict = valve_train_parameter_units()

__all__ = ["paper", "paper_damped", "valve_train", "REALISTIC_DAMPING_RATIO", "VALVE_TRAIN_PARAMETERS"]
