"""
camfollower compiled core (use the camfollower package, not this module directly)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['ArmTurn', 'CamFollowerModel', 'Defects', 'DiskCam', 'Mechanism', 'MechanismBuilder', 'MotionLaw', 'MotionProgram', 'OscillatingFlat', 'OscillatingRoller', 'Parameters', 'PeakCoefficients', 'Segment', 'TranslatingFlat', 'TranslatingRoller', 'paper_preset']
class PeakCoefficients:
    """
    Peaks of |V|, |A|, |J| of a normalized law.
    """
    def __repr__(self) -> str:
        ...
    @property
    def acceleration(self) -> float:
        ...
    @property
    def jerk(self) -> float:
        ...
    @property
    def velocity(self) -> float:
        ...
class MotionLaw:
    """
    Normalized motion law S(x) on x in [0, 1], S(0) = 0, S(1) = 1. Build one with a static method (MotionLaw.modified_trapezoid(), ...).
    """
    @staticmethod
    def constant_acceleration() -> MotionLaw:
        ...
    @staticmethod
    def cycloidal() -> MotionLaw:
        ...
    @staticmethod
    def dwell() -> MotionLaw:
        ...
    @staticmethod
    def modified_sine() -> MotionLaw:
        ...
    @staticmethod
    def modified_trapezoid() -> MotionLaw:
        ...
    @staticmethod
    def polynomial_345() -> MotionLaw:
        ...
    @staticmethod
    def polynomial_4567() -> MotionLaw:
        ...
    @staticmethod
    def simple_harmonic() -> MotionLaw:
        ...
    @staticmethod
    def sine_constant_cosine(b: typing.SupportsFloat | typing.SupportsIndex, c: typing.SupportsFloat | typing.SupportsIndex, d: typing.SupportsFloat | typing.SupportsIndex) -> MotionLaw:
        """
        Sine-constant-cosine acceleration family; b + c + d = 1 (fractions of the segment).
        """
    def __getstate__(self) -> tuple[int, float, float, float]:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, x: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        S, V, A, J at x (scalar or array, each in [0, 1]) as a dict.
        """
    def peaks(self) -> PeakCoefficients:
        """
        Peak coefficients C_v, C_a, C_j.
        """
    @property
    def b(self) -> float:
        ...
    @property
    def c(self) -> float:
        ...
    @property
    def d(self) -> float:
        ...
    @property
    def name(self) -> str:
        ...
class Segment:
    """
    One segment of a motion program (angles in rad, lifts in m).
    """
    def __getstate__(self) -> tuple[MotionLaw, float, float, float, float]:
        ...
    def __init__(self, law: MotionLaw, theta_start: typing.SupportsFloat | typing.SupportsIndex, theta_end: typing.SupportsFloat | typing.SupportsIndex, h_start: typing.SupportsFloat | typing.SupportsIndex, h_end: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def h_end(self) -> float:
        ...
    @property
    def h_start(self) -> float:
        ...
    @property
    def law(self) -> MotionLaw:
        ...
    @property
    def theta_end(self) -> float:
        ...
    @property
    def theta_start(self) -> float:
        ...
class MotionProgram:
    """
    Segments tiling one revolution; h(theta) and its theta-derivatives.
    """
    @staticmethod
    def paper_default(total_rise: typing.SupportsFloat | typing.SupportsIndex = 0.01) -> MotionProgram:
        """
        Paper Table 1: dwell 0-30, modified-trapezoid rise 30-180, dwell 180-210, return 210-360 deg.
        """
    def __getstate__(self) -> tuple[list[Segment]]:
        ...
    def __init__(self, segments: collections.abc.Sequence[Segment]) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Lift h (m) and dh/dtheta, d2h/dtheta2, d3h/dtheta3 at theta (rad; scalar or array) as a dict.
        """
    def max_lift(self) -> float:
        ...
    def min_lift(self) -> float:
        ...
    @property
    def segments(self) -> list[Segment]:
        ...
class DiskCam:
    """
    Disk cam with an offset translating roller follower (lengths in m, angles in rad).
    """
    def __init__(self, program: MotionProgram | None = None, base_radius: typing.SupportsFloat | typing.SupportsIndex = 0.03, roller_radius: typing.SupportsFloat | typing.SupportsIndex = 0.008, offset: typing.SupportsFloat | typing.SupportsIndex = 0.01) -> None:
        ...
    def max_pressure_angle_return(self, offset: typing.SupportsFloat | typing.SupportsIndex | None = None) -> tuple[float, float]:
        """
        (theta, alpha) in rad of the largest |alpha| on the returns.
        """
    def max_pressure_angle_rise(self, offset: typing.SupportsFloat | typing.SupportsIndex | None = None) -> tuple[float, float]:
        """
        (theta, alpha) in rad of the largest |alpha| on the rises.
        """
    def min_surface_radius(self, offset: typing.SupportsFloat | typing.SupportsIndex | None = None, flanks_only: bool = False) -> tuple[float, float]:
        """
        (theta, radius) of the smallest convex cam-surface radius of curvature (m).
        """
    def profile(self, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], offset: typing.SupportsFloat | typing.SupportsIndex | None = None) -> dict:
        """
        Profile quantities at theta (rad, scalar or array) for the nominal or a perturbed offset (m).
        Keys: h, R, dR, d2R (m, per rad), pressure_angle, dalpha (rad), normal_x/y (unit, follower
        frame: x lateral, y axial), pitch_x/y and surface_x/y (cam frame, m), pitch_curvature (1/m),
        surface_radius (m, signed: > 0 convex).
        """
    def write_surface_csv(self, path: str, points: typing.SupportsInt | typing.SupportsIndex = 3600) -> None:
        """
        Write the closed cam surface as CSV (theta_rad,x_m,y_m; points + 1 rows, last = first).
        """
    @property
    def base_radius(self) -> float:
        ...
    @property
    def offset(self) -> float:
        ...
    @property
    def program(self) -> MotionProgram:
        ...
    @property
    def roller_radius(self) -> float:
        ...
class Parameters:
    """
    Parameters of the 7-DOF model (SI units; paper Table 2 defaults). Override any by keyword:
    Parameters(contact_stiffness=2e8, camshaft_speed_rpm=1000). Parameters.names() lists them.
    """
    @staticmethod
    def names() -> list[str]:
        ...
    def __init__(self, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def get(self, name: str) -> float:
        ...
    def replace(self, **kwargs) -> Parameters:
        """
        A copy with the given parameters changed (validated); Parameters are immutable.
        """
    def to_dict(self) -> dict:
        ...
    @property
    def base_radius(self) -> float:
        """
        base_radius (m); read-only: use replace(base_radius=...)
        """
    @property
    def bearing_damping_horizontal(self) -> float:
        """
        bearing_damping_horizontal (N s/m); read-only: use replace(bearing_damping_horizontal=...)
        """
    @property
    def bearing_damping_vertical(self) -> float:
        """
        bearing_damping_vertical (N s/m); read-only: use replace(bearing_damping_vertical=...)
        """
    @property
    def bearing_stiffness_horizontal(self) -> float:
        """
        bearing_stiffness_horizontal (N/m); read-only: use replace(bearing_stiffness_horizontal=...)
        """
    @property
    def bearing_stiffness_vertical(self) -> float:
        """
        bearing_stiffness_vertical (N/m); read-only: use replace(bearing_stiffness_vertical=...)
        """
    @property
    def camshaft_mass(self) -> float:
        """
        camshaft_mass (kg); read-only: use replace(camshaft_mass=...)
        """
    @property
    def camshaft_speed_rpm(self) -> float:
        """
        camshaft_speed_rpm (rpm); read-only: use replace(camshaft_speed_rpm=...)
        """
    @property
    def contact_exponent(self) -> float:
        """
        contact_exponent (-); read-only: use replace(contact_exponent=...)
        """
    @property
    def contact_stiffness(self) -> float:
        """
        contact_stiffness (N/m^n); read-only: use replace(contact_stiffness=...)
        """
    @property
    def follower_mass(self) -> float:
        """
        follower_mass (kg); read-only: use replace(follower_mass=...)
        """
    @property
    def follower_rod_mass(self) -> float:
        """
        follower_rod_mass (kg); read-only: use replace(follower_rod_mass=...)
        """
    @property
    def gravity(self) -> float:
        """
        gravity (m/s^2); read-only: use replace(gravity=...)
        """
    @property
    def guide_stiffness(self) -> float:
        """
        guide_stiffness (N/m); read-only: use replace(guide_stiffness=...)
        """
    @property
    def offset(self) -> float:
        """
        offset (m); read-only: use replace(offset=...)
        """
    @property
    def omega(self) -> float:
        """
        camshaft speed, rad/s
        """
    @property
    def reference_speed(self) -> float:
        """
        reference_speed (m/s); read-only: use replace(reference_speed=...)
        """
    @property
    def restitution(self) -> float:
        """
        restitution (-); read-only: use replace(restitution=...)
        """
    @property
    def rod_damping(self) -> float:
        """
        rod_damping (N s/m); read-only: use replace(rod_damping=...)
        """
    @property
    def rod_stiffness(self) -> float:
        """
        rod_stiffness (N/m); read-only: use replace(rod_stiffness=...)
        """
    @property
    def roller_mass(self) -> float:
        """
        roller_mass (kg); read-only: use replace(roller_mass=...)
        """
    @property
    def roller_pin_stiffness_horizontal(self) -> float:
        """
        roller_pin_stiffness_horizontal (N/m); read-only: use replace(roller_pin_stiffness_horizontal=...)
        """
    @property
    def roller_pin_stiffness_vertical(self) -> float:
        """
        roller_pin_stiffness_vertical (N/m); read-only: use replace(roller_pin_stiffness_vertical=...)
        """
    @property
    def roller_radius(self) -> float:
        """
        roller_radius (m); read-only: use replace(roller_radius=...)
        """
    @property
    def spring_preload_deflection(self) -> float:
        """
        spring_preload_deflection (m); read-only: use replace(spring_preload_deflection=...)
        """
    @property
    def spring_stiffness(self) -> float:
        """
        spring_stiffness (N/m); read-only: use replace(spring_stiffness=...)
        """
class Defects:
    """
    Camshaft eccentricity and follower backlash (m; phase and switch width in rad). Both off by default.
    """
    def __init__(self, eccentricity: typing.SupportsFloat | typing.SupportsIndex = 0.0, eccentricity_phase: typing.SupportsFloat | typing.SupportsIndex = 0.0, backlash: typing.SupportsFloat | typing.SupportsIndex = 0.0, backlash_switch_width: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def backlash(self) -> float:
        ...
    @property
    def backlash_switch_width(self) -> float:
        ...
    @property
    def eccentricity(self) -> float:
        ...
    @property
    def eccentricity_phase(self) -> float:
        ...
class CamFollowerModel:
    """
    The paper's 7-DOF flexible cam-follower model. q = (y1, y2, y3, y4, x1, x2, x3): y along the
    follower axis, x across it; 1 camshaft, 2 roller, 3 follower rod, 4 follower top. Absolute
    displacements from the unloaded touching configuration (y2..y4 carry the lift h).
    """
    dof_names: typing.ClassVar[list] = ['y1', 'y2', 'y3', 'y4', 'x1', 'x2', 'x3']
    def __init__(self, parameters: Parameters | None = None, program: MotionProgram | None = None, defects: Defects | None = None) -> None:
        ...
    def contact(self, t: typing.SupportsFloat | typing.SupportsIndex, q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[7, 1]"], v: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[7, 1]"]) -> dict:
        """
        Contact state at time t for displacements q and velocities v (diagnostics).
        """
    def modal_analysis(self, theta: typing.SupportsFloat | typing.SupportsIndex = 0.0, with_contact: bool = True) -> dict:
        """
        Undamped natural frequencies (Hz, ascending) and mass-normalized mode shapes (columns) of the
        model linearized at the quasi-static equilibrium at cam angle theta (rad).
        """
    def static_equilibrium(self, theta: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 1]"]:
        """
        Quasi-static equilibrium at cam angle theta (rad).
        """
    def with_parameters(self, **kwargs) -> CamFollowerModel:
        """
        A new model with the given parameters changed (the model itself is immutable).
        """
    @property
    def cam(self) -> DiskCam:
        ...
    @property
    def damping_matrix(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 7]"]:
        ...
    @property
    def defects(self) -> Defects:
        ...
    @property
    def initial_state(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 1]"]:
        """
        static equilibrium at t = 0 (m)
        """
    @property
    def mass_matrix(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 7]"]:
        ...
    @property
    def omega(self) -> float:
        """
        rad/s
        """
    @property
    def parameters(self) -> Parameters:
        ...
    @property
    def period(self) -> float:
        """
        one camshaft revolution, s
        """
    @property
    def spring_preload(self) -> float:
        """
        P (N): return-spring force on y4 is -(P + K_rs y4)
        """
    @property
    def stiffness_matrix(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[7, 7]"]:
        ...
class ArmTurn:
    """
    Sense in which an oscillating follower's arm turns to lift.
    
    Members:
    
      counter_clockwise
    
      clockwise
    """
    __members__: typing.ClassVar[dict[str, ArmTurn]]
    clockwise: typing.ClassVar[ArmTurn]
    counter_clockwise: typing.ClassVar[ArmTurn]
    @typing.overload
    def __eq__(self, other: ArmTurn) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: ArmTurn) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class TranslatingRoller:
    """
    Translating roller follower with offset (m): the paper's follower.
    """
    def __getstate__(self) -> tuple[float, float, float]:
        ...
    def __init__(self, base_radius: typing.SupportsFloat | typing.SupportsIndex, roller_radius: typing.SupportsFloat | typing.SupportsIndex, offset: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def check(self, program: MotionProgram) -> None:
        """
        Raise ValueError naming the cam angle if the cam undercuts, has a cusp or the pressure angle reaches 90 deg.
        """
    def contact(self, program: MotionProgram, theta: typing.SupportsFloat | typing.SupportsIndex) -> dict:
        """
        Contact geometry at cam angle theta (rad): unit normal (ground frame), lever, lift and their theta-rates.
        """
    def max_pressure_angle(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, alpha) in rad of the largest |pressure angle| over the revolution.
        """
    def min_surface_radius(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, radius) of the smallest convex cam-surface radius of curvature (m).
        """
    def profile(self, program: MotionProgram, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Cam profile at theta (rad, scalar or array): surface and reference points in the cam frame (m), the
        contact point in the ground frame (m), surface radius of curvature (m, > 0 convex), pressure angle.
        """
    @property
    def base_radius(self) -> float:
        ...
    @property
    def offset(self) -> float:
        ...
    @property
    def roller_radius(self) -> float:
        ...
class TranslatingFlat:
    """
    Translating flat-faced follower: face angle (rad) from the normal to the axis, offset (m).
    """
    def __getstate__(self) -> tuple[float, float, float]:
        ...
    def __init__(self, base_radius: typing.SupportsFloat | typing.SupportsIndex, face_angle: typing.SupportsFloat | typing.SupportsIndex = 0.0, offset: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def check(self, program: MotionProgram) -> None:
        """
        Raise ValueError naming the cam angle if the cam undercuts, has a cusp or the pressure angle reaches 90 deg.
        """
    def contact(self, program: MotionProgram, theta: typing.SupportsFloat | typing.SupportsIndex) -> dict:
        """
        Contact geometry at cam angle theta (rad): unit normal (ground frame), lever, lift and their theta-rates.
        """
    def max_pressure_angle(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, alpha) in rad of the largest |pressure angle| over the revolution.
        """
    def min_surface_radius(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, radius) of the smallest convex cam-surface radius of curvature (m).
        """
    def profile(self, program: MotionProgram, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Cam profile at theta (rad, scalar or array): surface and reference points in the cam frame (m), the
        contact point in the ground frame (m), surface radius of curvature (m, > 0 convex), pressure angle.
        """
    @property
    def base_radius(self) -> float:
        ...
    @property
    def face_angle(self) -> float:
        ...
    @property
    def offset(self) -> float:
        ...
class OscillatingRoller:
    """
    Oscillating (swing-arm) roller follower: pivot (x, y) in m in the ground frame, arm length (m); its lift program is the arm rotation in rad.
    """
    def __getstate__(self) -> tuple[float, float, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, str]:
        ...
    def __init__(self, base_radius: typing.SupportsFloat | typing.SupportsIndex, roller_radius: typing.SupportsFloat | typing.SupportsIndex, pivot: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], arm_length: typing.SupportsFloat | typing.SupportsIndex, turn: str = 'counter_clockwise') -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def check(self, program: MotionProgram) -> None:
        """
        Raise ValueError naming the cam angle if the cam undercuts, has a cusp or the pressure angle reaches 90 deg.
        """
    def contact(self, program: MotionProgram, theta: typing.SupportsFloat | typing.SupportsIndex) -> dict:
        """
        Contact geometry at cam angle theta (rad): unit normal (ground frame), lever, lift and their theta-rates.
        """
    def max_pressure_angle(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, alpha) in rad of the largest |pressure angle| over the revolution.
        """
    def min_surface_radius(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, radius) of the smallest convex cam-surface radius of curvature (m).
        """
    def profile(self, program: MotionProgram, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Cam profile at theta (rad, scalar or array): surface and reference points in the cam frame (m), the
        contact point in the ground frame (m), surface radius of curvature (m, > 0 convex), pressure angle.
        """
    @property
    def arm_length(self) -> float:
        ...
    @property
    def base_radius(self) -> float:
        ...
    @property
    def pivot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        ...
    @property
    def roller_radius(self) -> float:
        ...
    @property
    def start_angle(self) -> float:
        """
        arm angle on the base circle, rad
        """
    @property
    def turn(self) -> str:
        ...
class OscillatingFlat:
    """
    Oscillating flat-faced follower: pivot (x, y) in m, face offset from the pivot (m); its lift program is the arm rotation in rad.
    """
    def __getstate__(self) -> tuple[float, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, str]:
        ...
    def __init__(self, base_radius: typing.SupportsFloat | typing.SupportsIndex, pivot: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], face_offset: typing.SupportsFloat | typing.SupportsIndex = 0.0, turn: str = 'counter_clockwise') -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def check(self, program: MotionProgram) -> None:
        """
        Raise ValueError naming the cam angle if the cam undercuts, has a cusp or the pressure angle reaches 90 deg.
        """
    def contact(self, program: MotionProgram, theta: typing.SupportsFloat | typing.SupportsIndex) -> dict:
        """
        Contact geometry at cam angle theta (rad): unit normal (ground frame), lever, lift and their theta-rates.
        """
    def max_pressure_angle(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, alpha) in rad of the largest |pressure angle| over the revolution.
        """
    def min_surface_radius(self, program: MotionProgram) -> tuple[float, float]:
        """
        (theta, radius) of the smallest convex cam-surface radius of curvature (m).
        """
    def profile(self, program: MotionProgram, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Cam profile at theta (rad, scalar or array): surface and reference points in the cam frame (m), the
        contact point in the ground frame (m), surface radius of curvature (m, > 0 convex), pressure angle.
        """
    @property
    def base_radius(self) -> float:
        ...
    @property
    def face_offset(self) -> float:
        ...
    @property
    def pivot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        ...
    @property
    def start_angle(self) -> float:
        """
        face-normal angle on the base circle, rad
        """
    @property
    def turn(self) -> str:
        ...
class MechanismBuilder:
    """
    Describe a cam mechanism: DOFs with masses, springs and dampers between DOFs or to 'ground', loads,
    gravity, global damping, and cam-follower contact pairs. build() makes the immutable Mechanism.
    SI units: kg (kg m^2 for a rotation), N/m, N s/m, N; angles in rad.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def add_contact(self, name: str, program: MotionProgram, follower: typing.Any, *, follower_dof: str, stiffness: typing.SupportsFloat | typing.SupportsIndex, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0, cam_x: str = 'ground', cam_y: str = 'ground', lateral: str = 'ground') -> None:
        """
        A cam-follower contact pair: the cam's lift program (m, or rad for an oscillating follower), the follower
        type, the DOF of the follower's coordinate, a Hertz law F = k delta^n (1 + chi delta'), the cam's
        phase on the shaft (rad), the cam centre's DOFs and a translating follower's lateral DOF.
        """
    def add_damper(self, name: str, a: str, b: str = 'ground', *, damping: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def add_dof(self, name: str, mass: typing.SupportsFloat | typing.SupportsIndex, direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ...) -> None:
        """
        A DOF: mass (kg, or kg m^2 for a rotation) and, for a translation, its unit direction in space (for gravity).
        """
    def add_load(self, dof: str, force: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Constant load along +q (N).
        """
    def add_spring(self, name: str, a: str, b: str = 'ground', *, stiffness: typing.SupportsFloat | typing.SupportsIndex, damping: typing.SupportsFloat | typing.SupportsIndex = 0.0, preload: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        Spring-damper between DOFs a and b (or 'ground'); force on a: -(preload + k (q_a - q_b) + c (v_a - v_b)).
        """
    def build(self) -> ...:
        """
        Validate and assemble the immutable Mechanism.
        """
    def set_gravity(self, gravity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        """
        Gravity vector (m/s^2).
        """
    def set_modal_damping(self, ratios: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        """
        C += modal damping with these ratios (one for all modes, or one per mode, ascending), over the modes at the initial equilibrium with the contacts linearized.
        """
    def set_rayleigh_damping(self, alpha: typing.SupportsFloat | typing.SupportsIndex, beta: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        C += alpha M + beta K.
        """
    @property
    def camshaft_speed_rpm(self) -> float:
        ...
    @camshaft_speed_rpm.setter
    def camshaft_speed_rpm(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def dof_names(self) -> list[str]:
        ...
class Mechanism:
    """
    An immutable cam mechanism (build one with MechanismBuilder, or camfollower.presets).
    simulate(mechanism, ...) integrates it; channels: theta and per contact <name>.force,
    .penetration, .stiffness, .pressure_angle, .cam_angle, .in_contact.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, builder: MechanismBuilder) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def builder(self) -> MechanismBuilder:
        """
        A copy of the description it was built from: change it and build() a changed mechanism.
        """
    def modal_analysis(self, theta: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> dict:
        """
        Undamped natural frequencies (Hz, ascending), mass-normalized mode shapes and the tangent stiffness at
        the quasi-static equilibrium at camshaft angle theta (rad), contacts linearized.
        """
    def static_equilibrium(self, theta: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Quasi-static equilibrium at camshaft angle theta (rad).
        """
    def with_camshaft_speed_rpm(self, rpm: typing.SupportsFloat | typing.SupportsIndex) -> Mechanism:
        """
        The same mechanism at another camshaft speed (a new object).
        """
    @property
    def camshaft_speed_rpm(self) -> float:
        ...
    @property
    def contact_names(self) -> list[str]:
        ...
    @property
    def damping(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def dof_names(self) -> list[str]:
        ...
    @property
    def initial_state(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        static equilibrium at t = 0 (m or rad per DOF)
        """
    @property
    def mass(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def omega(self) -> float:
        """
        rad/s
        """
    @property
    def period(self) -> float:
        """
        one camshaft revolution, s
        """
    @property
    def size(self) -> int:
        ...
    @property
    def stiffness(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
@typing.overload
def _run(system: CamFollowerModel, duration: typing.SupportsFloat | typing.SupportsIndex, time_step: typing.SupportsFloat | typing.SupportsIndex, decimation: typing.SupportsInt | typing.SupportsIndex, gamma: typing.SupportsFloat | typing.SupportsIndex | None, beta: typing.SupportsFloat | typing.SupportsIndex | None, hht_alpha: typing.SupportsFloat | typing.SupportsIndex, linear_solver: str, residual_tolerance: typing.SupportsFloat | typing.SupportsIndex, increment_tolerance: typing.SupportsFloat | typing.SupportsIndex, max_iterations: typing.SupportsInt | typing.SupportsIndex, max_halvings: typing.SupportsInt | typing.SupportsIndex, record_from: typing.SupportsFloat | typing.SupportsIndex, max_output_bytes: typing.SupportsFloat | typing.SupportsIndex, progress: typing.Any, progress_interval: typing.SupportsFloat | typing.SupportsIndex) -> dict:
    """
    Internal: camfollower.simulate() calls this and wraps the output in a Result.
    """
@typing.overload
def _run(system: Mechanism, duration: typing.SupportsFloat | typing.SupportsIndex, time_step: typing.SupportsFloat | typing.SupportsIndex, decimation: typing.SupportsInt | typing.SupportsIndex, gamma: typing.SupportsFloat | typing.SupportsIndex | None, beta: typing.SupportsFloat | typing.SupportsIndex | None, hht_alpha: typing.SupportsFloat | typing.SupportsIndex, linear_solver: str, residual_tolerance: typing.SupportsFloat | typing.SupportsIndex, increment_tolerance: typing.SupportsFloat | typing.SupportsIndex, max_iterations: typing.SupportsInt | typing.SupportsIndex, max_halvings: typing.SupportsInt | typing.SupportsIndex, record_from: typing.SupportsFloat | typing.SupportsIndex, max_output_bytes: typing.SupportsFloat | typing.SupportsIndex, progress: typing.Any, progress_interval: typing.SupportsFloat | typing.SupportsIndex) -> dict:
    """
    Internal: camfollower.simulate() calls this and wraps the output in a Result.
    """
def paper_preset(parameters: Parameters | None = None, program: MotionProgram | None = None) -> Mechanism:
    """
    The paper's 7-DOF model (Tounsi et al.) built from the mechanism parts; DOFs y1..y4, x1..x3,
    contact 'cam'. Parameters as for CamFollowerModel (Table 2 defaults).
    """
