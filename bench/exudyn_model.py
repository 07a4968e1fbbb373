# SPDX-License-Identifier: BSD-3-Clause
"""The paper's 7-DOF lumped cam-follower model built in Exudyn and integrated by its implicit solver.

    python3 bench/exudyn_model.py        # needs `pip install exudyn` (written against 1.13.6)

Used by bench/compare.py (``run_exudyn``); run on its own, it integrates one revolution at a few
step sizes and prints the error in the follower displacement y4 against camfollower.

Construction, as an Exudyn user would write it (only the data come from camfollower:
masses, spring and damper constants from the parameter card ``PARAMETERS``, the preload, the cam lift h(theta),
the contact constants and the static equilibrium through ``camfollower.reference.NumpyCamFollower``):

- one ``Node1D`` per DOF q = (y1, y2, y3, y4, x1, x2, x3), started at the static equilibrium
  ``ref.q0`` at rest, each carrying a ``Mass1D``;
- the seven linear springs/dampers as ``CoordinateSpringDamper`` between ``MarkerNodeCoordinate``
  markers, to a ``NodePointGround`` for the grounded ones: y1-ground (K_vs, C_vs), x1-ground
  (K_hs, C_hs), y2-y3 (K_vc), x2-x3 (K_hc), x3-ground (K_rb), y3-y4 (K_f, C_f), y4-ground (K_rs);
- the spring preload as a ``LoadCoordinate`` on y4 (``ref.external[3]``, about -182 N);
- the cam-roller contact as an ``ObjectGenericODE2`` on the four nodes it couples (y1, y2, x1, x2)
  with a zero mass matrix (the masses are the Mass1D objects). With theta = omega t, R = s0 + h,
  p = h' - e, c = R/hypot(R, p), s = p/hypot(R, p): direction g = (c, -c, -s, s) on (y1, y2, x1, x2),
  penetration delta = g.q + h c, force F = K_h max(delta, 0). Exudyn puts the user force on the
  right-hand side (M q'' + D q' + K q = f + f_user), so ``forceUserFunction`` returns -F g; its
  ``jacobianUserFunction`` returns the derivative of the left-hand side, f_ODE2 K_h g g^T in contact
  (zero otherwise), so Newton uses the exact Jacobian instead of numerical differentiation. The
  cam geometry at time t is computed once per time (the residual and the Jacobian of one Newton
  iteration are evaluated at the same t).

Solver: Exudyn's implicit second-order solver (``exu.MainSolverImplicitSecondOrder``, what
``mbs.SolveDynamic`` runs) with the generalized-alpha method at spectralRadius = 1, which Exudyn
reports as alpha_m = alpha_f = 1/2, beta = 1/4, gamma = 1/2: the undamped trapezoidal rule, i.e. the
same Newmark average-acceleration scheme camfollower uses (at equal step the two agree to round-off,
see the table printed by this script). Fixed step (adaptiveStep off), initial accelerations computed
from the equations of motion, full Newton (useModifiedNewton off, Jacobian in every iteration),
relative residual tolerance 1e-10 and absolute residual tolerance 1e-8 N: the residual's round-off
floor is a few 1e-10 N (2.5e8 N/m springs times coordinates of up to centimetres), so a tighter
absolute tolerance makes Newton stall. No solution file.

Recording: two sensors stored in memory (``storeInternal``, no file), written every
``record_every`` steps: the y4 node coordinate and the four contact coordinates of the
GenericODE2 object. The contact force is computed after the solve from the recorded contact
coordinates, with the same contact function the user function uses, so recording costs no
Python call during the solve. ``wall_time_s`` is the time of the solver's ``SolveSystem`` only
(the model is built and assembled before).
"""

from __future__ import annotations

import math
import time

import camfollower as cf
import exudyn as exu
import numpy as np
from camfollower.reference import NumpyCamFollower
from exudyn.itemInterface import (
    CoordinateSpringDamper,
    LoadCoordinate,
    MarkerNodeCoordinate,
    Mass1D,
    Node1D,
    NodePointGround,
    ObjectGenericODE2,
    SensorBody,
    SensorNode,
)

Y1, Y2, Y3, Y4, X1, X2, X3 = range(7)
CONTACT_DOFS = (Y1, Y2, X1, X2)  # the coordinates of the contact object, in this order

PARAMETERS = cf.Parameters()  # the paper's card (Table 2): the preset and the springs below
NEWTON_RELATIVE_TOLERANCE = 1e-10
NEWTON_ABSOLUTE_TOLERANCE = 1e-8  # N


def springs(p):
    """(dof a, dof b or None for ground, stiffness, damping) of the seven linear connections."""
    return [
        (Y1, None, p.bearing_stiffness_vertical, p.bearing_damping_vertical),  # K_vs, C_vs
        (X1, None, p.bearing_stiffness_horizontal, p.bearing_damping_horizontal),  # K_hs, C_hs
        (Y2, Y3, p.roller_pin_stiffness_vertical, 0.0),  # K_vc
        (X2, X3, p.roller_pin_stiffness_horizontal, 0.0),  # K_hc
        (X3, None, p.guide_stiffness, 0.0),  # K_rb
        (Y3, Y4, p.rod_stiffness, p.rod_damping),  # K_f, C_f
        (Y4, None, p.spring_stiffness, 0.0),  # K_rs
    ]


class CamContact:
    """Linear unilateral cam-roller contact on (y1, y2, x1, x2); geometry cached for the last time."""

    def __init__(self, ref: NumpyCamFollower):
        self.kh, self.s0, self.e, self.omega, self.program = ref.kh, ref.s0, ref.e, ref.omega, ref.program
        self._t = None

    def geometry(self, t):
        """Direction g on (y1, y2, x1, x2) and the lift part h c of the penetration at time t."""
        if t != self._t:
            m = self.program.evaluate(self.omega * t)
            R = self.s0 + m["h"]
            p = m["dh"] - self.e
            norm = math.hypot(R, p)
            c, s = R / norm, p / norm
            self._t, self._g, self._lift = t, np.array([c, -c, -s, s]), m["h"] * c
        return self._g, self._lift

    def force(self, t, q):
        """Contact force F = K_h max(delta, 0) for the contact coordinates q."""
        g, lift = self.geometry(t)
        return self.kh * max(float(g @ q) + lift, 0.0)

    def force_user_function(self, mbs, t, itemNumber, q, q_t):
        """Generalized force on the right-hand side: -F g."""
        g, lift = self.geometry(t)
        delta = float(g @ q) + lift
        return -self.kh * delta * g if delta > 0.0 else np.zeros(4)

    def jacobian_user_function(self, mbs, t, itemNumber, q, q_t, fODE2, fODE2_t):
        """Derivative of the left-hand-side term F g: fODE2 K_h g g^T in contact."""
        g, lift = self.geometry(t)
        if float(g @ q) + lift > 0.0:
            return (fODE2 * self.kh) * np.outer(g, g)
        return np.zeros((4, 4))


def build(model):
    """Exudyn system of the model at its static equilibrium: (mbs, y4 sensor, contact sensor, contact)."""
    ref = NumpyCamFollower(model)
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
    ground_marker = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))

    nodes, markers = [], []
    for k in range(7):
        node = mbs.AddNode(Node1D(referenceCoordinates=[0.0], initialCoordinates=[ref.q0[k]], initialVelocities=[0.0]))
        mbs.AddObject(Mass1D(mass=ref.M[k, k], nodeNumber=node))
        nodes.append(node)
        markers.append(mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=0)))

    for a, b, stiffness, damping in springs(PARAMETERS):
        other = ground_marker if b is None else markers[b]
        mbs.AddObject(CoordinateSpringDamper(markerNumbers=[other, markers[a]], stiffness=stiffness, damping=damping))
    mbs.AddLoad(LoadCoordinate(markerNumber=markers[Y4], load=ref.external[Y4]))

    contact = CamContact(ref)
    contact_object = mbs.AddObject(
        ObjectGenericODE2(
            nodeNumbers=[nodes[k] for k in CONTACT_DOFS],
            massMatrix=np.zeros((4, 4)),
            forceUserFunction=contact.force_user_function,
            jacobianUserFunction=contact.jacobian_user_function,
        )
    )

    y4_sensor = mbs.AddSensor(
        SensorNode(nodeNumber=nodes[Y4], storeInternal=True, outputVariableType=exu.OutputVariableType.Coordinates)
    )
    contact_sensor = mbs.AddSensor(
        SensorBody(bodyNumber=contact_object, storeInternal=True, outputVariableType=exu.OutputVariableType.Coordinates)
    )
    mbs.Assemble()
    return mbs, y4_sensor, contact_sensor, contact


def simulation_settings(duration, steps, record_every):
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.solverType = exu.DynamicSolverType.GeneralizedAlpha
    ti.generalizedAlpha.spectralRadius = 1.0
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.startTime, ti.endTime, ti.numberOfSteps = 0.0, duration, steps
    ti.adaptiveStep = False
    ti.newton.useModifiedNewton = False
    ti.newton.relativeTolerance = NEWTON_RELATIVE_TOLERANCE
    ti.newton.absoluteTolerance = NEWTON_ABSOLUTE_TOLERANCE
    ti.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = record_every * duration / steps
    s.show.statistics = False
    s.show.computationTime = False
    return s


def run_exudyn(model, duration, time_step, record_every=1) -> dict:
    """Integrate with Exudyn's implicit solver from the static equilibrium; return
    {'t': array, 'y4': array (follower displacement), 'contact_force': array, 'steps': int, 'wall_time_s': float,
     'solver': short description string}, plus 'newton_iterations'."""
    steps = round(duration / time_step)
    if steps < 1 or abs(steps * time_step - duration) > 1e-9 * duration:
        raise ValueError("duration must be a whole number of time steps")
    mbs, y4_sensor, contact_sensor, contact = build(model)
    settings = simulation_settings(duration, steps, record_every)

    # mbs.SolveDynamic(settings) does the same through this solver object, and afterwards warns that
    # the Python user functions allocate NumPy arrays in every step, which is expected here.
    solver = exu.MainSolverImplicitSecondOrder()
    t0 = time.perf_counter()
    ok = solver.SolveSystem(mbs, settings)
    wall = time.perf_counter() - t0
    if not ok:
        raise RuntimeError(f"Exudyn solver failed at t = {solver.it.currentTime} s")

    y4 = mbs.GetSensorStoredData(y4_sensor)
    q = mbs.GetSensorStoredData(contact_sensor)
    force = np.array([contact.force(t, row) for t, row in zip(q[:, 0], q[:, 1:])])
    return {
        "t": y4[:, 0].copy(),
        "y4": y4[:, 1].copy(),
        "contact_force": force,
        "steps": steps,
        "newton_iterations": int(solver.it.newtonStepsCount),
        "wall_time_s": wall,
        "solver": (
            f"Exudyn {exu.__version__} generalized-alpha rho_inf=1 (trapezoidal), fixed step, full Newton "
            f"with analytic contact Jacobian, tol rel {NEWTON_RELATIVE_TOLERANCE:g} / "
            f"abs {NEWTON_ABSOLUTE_TOLERANCE:g} N"
        ),
    }


def main():
    model = cf.presets.paper(PARAMETERS)
    T = model.period
    ref_steps = 2**18
    ref = cf.simulate(model, revolutions=1, time_step=T / ref_steps)
    ref_y4, ref_force = ref["q"][:, 3], ref["cam.force"]
    print(f"reference: camfollower, one revolution at T/{ref_steps}")
    print(
        f"{'time step':>12s} {'steps':>6s} {'Newton it':>9s} {'wall (s)':>9s} {'err y4':>9s} {'err force':>9s}"
        f" {'vs camfollower same step':>25s}"
    )
    for n in (4096, 8192, 16384, 32768):
        r = run_exudyn(model, T, T / n)
        err_y4 = np.max(np.abs(r["y4"] - np.interp(r["t"], ref["t"], ref_y4))) / np.max(np.abs(ref_y4))
        err_force = np.max(np.abs(r["contact_force"] - np.interp(r["t"], ref["t"], ref_force))) / np.max(
            np.abs(ref_force)
        )
        same = cf.simulate(model, revolutions=1, time_step=T / n)
        err_same = np.max(np.abs(r["y4"] - same["q"][:, 3])) / np.max(np.abs(ref_y4))
        print(
            f"{f'T/{n}':>12s} {r['steps']:6d} {r['newton_iterations']:9d} {r['wall_time_s']:9.3f} "
            f"{err_y4:9.2e} {err_force:9.2e} {err_same:25.2e}",
            flush=True,
        )
    print(f"solver: {r['solver']}")
    print("errors: max |x - x_ref| / max |x_ref| over the recorded steps")


if __name__ == "__main__":
    main()
