"""
camfollower compiled core (use the camfollower package, not this module directly)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['CamFollowerModel', 'Defects', 'DiskCam', 'MotionLaw', 'MotionProgram', 'Parameters', 'PeakCoefficients', 'Segment']
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
    def __repr__(self) -> str:
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
    def __init__(self, law: MotionLaw, theta_start: typing.SupportsFloat | typing.SupportsIndex, theta_end: typing.SupportsFloat | typing.SupportsIndex, h_start: typing.SupportsFloat | typing.SupportsIndex, h_end: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __repr__(self) -> str:
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
    def __init__(self, segments: collections.abc.Sequence[Segment]) -> None:
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
    def set(self, name: str, value: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Set one parameter by name; validated (ValueError names the parameter and its range).
        """
    def to_dict(self) -> dict:
        ...
    @property
    def base_radius(self) -> float:
        """
        base_radius (m)
        """
    @base_radius.setter
    def base_radius(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bearing_damping_horizontal(self) -> float:
        """
        bearing_damping_horizontal (N s/m)
        """
    @bearing_damping_horizontal.setter
    def bearing_damping_horizontal(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bearing_damping_vertical(self) -> float:
        """
        bearing_damping_vertical (N s/m)
        """
    @bearing_damping_vertical.setter
    def bearing_damping_vertical(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bearing_stiffness_horizontal(self) -> float:
        """
        bearing_stiffness_horizontal (N/m)
        """
    @bearing_stiffness_horizontal.setter
    def bearing_stiffness_horizontal(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bearing_stiffness_vertical(self) -> float:
        """
        bearing_stiffness_vertical (N/m)
        """
    @bearing_stiffness_vertical.setter
    def bearing_stiffness_vertical(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def camshaft_mass(self) -> float:
        """
        camshaft_mass (kg)
        """
    @camshaft_mass.setter
    def camshaft_mass(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def camshaft_speed_rpm(self) -> float:
        """
        camshaft_speed_rpm (rpm)
        """
    @camshaft_speed_rpm.setter
    def camshaft_speed_rpm(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_exponent(self) -> float:
        """
        contact_exponent (-)
        """
    @contact_exponent.setter
    def contact_exponent(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def contact_stiffness(self) -> float:
        """
        contact_stiffness (N/m^n)
        """
    @contact_stiffness.setter
    def contact_stiffness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def follower_mass(self) -> float:
        """
        follower_mass (kg)
        """
    @follower_mass.setter
    def follower_mass(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def follower_rod_mass(self) -> float:
        """
        follower_rod_mass (kg)
        """
    @follower_rod_mass.setter
    def follower_rod_mass(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gravity(self) -> float:
        """
        gravity (m/s^2)
        """
    @gravity.setter
    def gravity(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def guide_stiffness(self) -> float:
        """
        guide_stiffness (N/m)
        """
    @guide_stiffness.setter
    def guide_stiffness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def offset(self) -> float:
        """
        offset (m)
        """
    @offset.setter
    def offset(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def omega(self) -> float:
        """
        camshaft speed, rad/s
        """
    @property
    def reference_speed(self) -> float:
        """
        reference_speed (m/s)
        """
    @reference_speed.setter
    def reference_speed(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def restitution(self) -> float:
        """
        restitution (-)
        """
    @restitution.setter
    def restitution(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rod_damping(self) -> float:
        """
        rod_damping (N s/m)
        """
    @rod_damping.setter
    def rod_damping(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def rod_stiffness(self) -> float:
        """
        rod_stiffness (N/m)
        """
    @rod_stiffness.setter
    def rod_stiffness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def roller_mass(self) -> float:
        """
        roller_mass (kg)
        """
    @roller_mass.setter
    def roller_mass(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def roller_pin_stiffness_horizontal(self) -> float:
        """
        roller_pin_stiffness_horizontal (N/m)
        """
    @roller_pin_stiffness_horizontal.setter
    def roller_pin_stiffness_horizontal(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def roller_pin_stiffness_vertical(self) -> float:
        """
        roller_pin_stiffness_vertical (N/m)
        """
    @roller_pin_stiffness_vertical.setter
    def roller_pin_stiffness_vertical(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def roller_radius(self) -> float:
        """
        roller_radius (m)
        """
    @roller_radius.setter
    def roller_radius(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def spring_preload_deflection(self) -> float:
        """
        spring_preload_deflection (m)
        """
    @spring_preload_deflection.setter
    def spring_preload_deflection(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def spring_stiffness(self) -> float:
        """
        spring_stiffness (N/m)
        """
    @spring_stiffness.setter
    def spring_stiffness(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
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
def _run(system: CamFollowerModel, duration: typing.SupportsFloat | typing.SupportsIndex, time_step: typing.SupportsFloat | typing.SupportsIndex, decimation: typing.SupportsInt | typing.SupportsIndex, gamma: typing.SupportsFloat | typing.SupportsIndex | None, beta: typing.SupportsFloat | typing.SupportsIndex | None, hht_alpha: typing.SupportsFloat | typing.SupportsIndex, linear_solver: str, residual_tolerance: typing.SupportsFloat | typing.SupportsIndex, increment_tolerance: typing.SupportsFloat | typing.SupportsIndex, max_iterations: typing.SupportsInt | typing.SupportsIndex, max_halvings: typing.SupportsInt | typing.SupportsIndex, record_from: typing.SupportsFloat | typing.SupportsIndex, max_output_bytes: typing.SupportsFloat | typing.SupportsIndex, progress: typing.Any, progress_interval: typing.SupportsFloat | typing.SupportsIndex) -> dict:
    """
    Internal: camfollower.simulate() calls this and wraps the output in a Result.
    """
