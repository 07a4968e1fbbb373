"""
camfollower compiled core (use the camfollower package, not this module directly)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['ArmTurn', 'BarrelArmRoller', 'BarrelRoller', 'BoundaryContinuity', 'CamEccentricity', 'ContinuityReport', 'CouplerLinkage', 'Elastic', 'Groove', 'LineContact', 'MAX_CAMSHAFT_SPEED', 'MAX_PART_LENGTH', 'MAX_POINTS', 'METHODS', 'MIN_CAMSHAFT_SPEED', 'Mechanism', 'MechanismBuilder', 'MotionLaw', 'MotionProgram', 'OscillatingFlat', 'OscillatingRoller', 'Parameters', 'PeakCoefficients', 'ProfileError', 'RUNGE_KUTTA_DEFAULT_TOLERANCE', 'SHOOTING_MAX_STATE_SIZE', 'SPARSE_BACKEND_THRESHOLD', 'Segment', 'SolverSettings', 'SpeedModulation', 'SpeedProgram', 'SpeedRamp', 'TranslatingFlat', 'TranslatingRoller', 'barrel_groove', 'cam_outline', 'check_output_target', 'length_units', 'paper_preset', 'realistic_damping_ratio', 'valve_train_parameter_units', 'valve_train_preset', 'write_barrel_groove_csv', 'write_cam_csv', 'write_file_atomically']
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
    A user-defined law (a lift table as a spline, a polynomial from boundary conditions) comes
    from Segment.from_table / Segment.polynomial / MotionProgram.from_table; it holds its lift in
    m relative to its segment's start (evaluate_lift), and evaluate/peaks give the normalized
    form only when its net lift is not zero.
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
    def __getstate__(self) -> tuple:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, x: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        S, V, A, J at x (scalar or array, each in [0, 1]) as a dict.
        """
    def evaluate_lift(self, u: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        A spline / polynomial law's lift relative to its segment start, h(theta_start + u) - h(theta_start)
        (m) and its derivatives dh, d2h, d3h (m/rad^k), u in [0, span] rad (scalar or array), as a dict.
        """
    def has_zero_end_acceleration(self) -> bool:
        """
        Whether S, V, A are continuous at both ends against a dwell (A = 0 at both ends, the law C2).
        """
    def lift_peaks(self) -> dict:
        """
        A spline / polynomial law's peaks of |h'|, |h''|, |h'''| (m/rad^k) and their angles as offsets from
        the segment start (rad): {'velocity': {'value', 'theta'}, 'acceleration': ..., 'jerk': ...}.
        """
    def peaks(self) -> PeakCoefficients:
        """
        Peak coefficients C_v, C_a, C_j. For a spline / polynomial law: found numerically, normalized by its
        span beta and net lift L (C_a = max|h''| beta^2 / |L|; inf when L = 0).
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
    def definition(self) -> typing.Any:
        """
        A spline / polynomial law's defining data as a dict (table, degree, smoothing, end
        derivatives; or span, end conditions, interior points, coefficients in x); None
        for a built-in law.
        """
    @property
    def is_custom(self) -> bool:
        """
        True for a spline or polynomial law.
        """
    @property
    def name(self) -> str:
        ...
class Segment:
    """
    One segment of a motion program (angles in rad, lifts in m).
    """
    @staticmethod
    def from_table(theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], h: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], degree: typing.SupportsInt | typing.SupportsIndex = 5, smoothing: typing.SupportsFloat | typing.SupportsIndex = 0.0, start_derivatives: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] = [], end_derivatives: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] = []) -> Segment:
        """
        A lift table as one segment: a B-spline of odd degree (1, 3, 5 or 7; 5 is C4) through the points
        (smoothing = 0) or a smoothing spline (smoothing = lambda >= 0, rad^degree: minimizes
        sum (s(theta_i) - h_i)^2 + lambda * integral (s^(m))^2, m = (degree + 1) / 2). theta absolute
        (rad, strictly increasing), h in m; the segment spans theta[0]..theta[-1] from h[0] to h[-1].
        start_derivatives / end_derivatives: h', h'', ... (m/rad^k, up to degree - 1 each) imposed at the
        ends, as are the end values; empty means zeros up to degree - 1 (joins a dwell C^(degree-1)).
        """
    @staticmethod
    def polynomial(theta_start: typing.SupportsFloat | typing.SupportsIndex, theta_end: typing.SupportsFloat | typing.SupportsIndex, start: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], end: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], interior: collections.abc.Sequence[tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]] = []) -> Segment:
        """
        The polynomial segment meeting start = [h, h', h'', ...] at theta_start and end likewise at theta_end
        (m, m/rad^k; at least h each) through the interior (theta, h) points (rad strictly inside, m).
        Degree = number of conditions - 1: ([0, 0, 0], [L, 0, 0]) is the 3-4-5 polynomial. Refuses
        repeated / outside interior points and ill-conditioned systems (ValueError).
        """
    def __getstate__(self) -> tuple[MotionLaw, float, float, float, float]:
        ...
    def __init__(self, law: MotionLaw, theta_start: typing.SupportsFloat | typing.SupportsIndex, theta_end: typing.SupportsFloat | typing.SupportsIndex, h_start: typing.SupportsFloat | typing.SupportsIndex, h_end: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def lift_at(self, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        The design lift h (m) and dh, d2h, d3h (m/rad^k) at theta in [theta_start, theta_end] (rad), as a dict.
        """
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
class ProfileError:
    """
    Manufacturing error of a cam as a lift error e(theta) (m, + = lift higher), as a cam-measuring machine
    reports it probing with the follower's own roller or face. An immutable sum of components (waviness,
    dent, Fourier series / fitted table) combined with +; attach it with MotionProgram.with_profile_error.
    ProfileError() is no error.
    """
    @staticmethod
    def dent(centre: typing.SupportsFloat | typing.SupportsIndex, width: typing.SupportsFloat | typing.SupportsIndex, depth: typing.SupportsFloat | typing.SupportsIndex) -> ProfileError:
        """
        Local dent e = -depth (1 - x^2)^4, x = (theta - centre) / (width / 2), zero for |x| >= 1 (C3 at
        its edges). centre and width in rad (0 < width <= pi), depth in m (> 0: material missing,
        < 0: a bump).
        """
    @staticmethod
    def fourier(mean: typing.SupportsFloat | typing.SupportsIndex, cos: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], sin: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> ProfileError:
        """
        e = mean + sum_k cos[k-1] cos(k theta) + sin[k-1] sin(k theta), k = 1..K (m).
        """
    @staticmethod
    def table(theta: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], error: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], max_harmonic: typing.SupportsInt | typing.SupportsIndex | None = None) -> ProfileError:
        """
        Least-squares Fourier fit of a measured table: theta (rad, >= 3 points, strictly increasing in
        [0, 2 pi), any spacing), error (m). max_harmonic in [1, (N - 1) // 2], default the upper end
        (interpolation for an odd number of equally spaced points); lower it to smooth a noisy table.
        """
    @staticmethod
    def waviness(amplitude: typing.SupportsFloat | typing.SupportsIndex, order: typing.SupportsInt | typing.SupportsIndex, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> ProfileError:
        """
        e = amplitude cos(order theta + phase): amplitude in m, order an integer >= 1 (waves per
        revolution), phase in rad.
        """
    def __add__(self, arg0: ProfileError) -> ProfileError:
        ...
    def __bool__(self) -> bool:
        ...
    def __getstate__(self) -> tuple:
        ...
    def __init__(self) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Lift error e (m) and de/dtheta, d2e/dtheta2, d3e/dtheta3 at theta (rad; scalar or array) as a dict.
        """
    def features(self) -> list[float]:
        """
        Angles (rad, ascending, in [0, 2 pi)) a sampled check must visit: dent centres and edges.
        """
    @property
    def components(self) -> list:
        """
        The components as dicts: {'kind': 'waviness' | 'dent' | 'fourier', and its parameters}.
        """
class BarrelArmRoller:
    """
    Barrel (cylindrical) cam with a swing-arm roller follower: the arm's pivot axis is radial, so the arm swings in the plane tangent to the cylinder; pivot (x across the station, y along the cam axis) in m; lift in rad.
    """
    translating: typing.ClassVar[bool] = False
    type_name: typing.ClassVar[str] = 'barrel_arm_roller'
    def __getstate__(self) -> tuple[float, float, float, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, str]:
        ...
    def __init__(self, cylinder_radius: typing.SupportsFloat | typing.SupportsIndex, groove_depth: typing.SupportsFloat | typing.SupportsIndex, roller_radius: typing.SupportsFloat | typing.SupportsIndex, pivot: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], arm_length: typing.SupportsFloat | typing.SupportsIndex, turn: ArmTurn | str = 'counter_clockwise') -> None:
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
    def arm_length(self) -> float:
        """
        pivot to roller centre L (m, > 0)
        """
    @property
    def cylinder_radius(self) -> float:
        """
        outer radius R of the barrel cam (m, > 0)
        """
    @property
    def groove_depth(self) -> float:
        """
        depth d of the groove (m, 0 < d < R); the pitch radius is R - d/2
        """
    @property
    def pivot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        arm pivot (m): x across the follower's station (against the surface's motion), y along the cam axis; |x| <= arm_length
        """
    @property
    def roller_radius(self) -> float:
        """
        roller radius r_r (m, > 0)
        """
    @property
    def start_angle(self) -> float:
        """
        start angle phi0 (rad, ground frame) of the arm at zero lift (a disk cam's: the roller on the base circle)
        """
    @property
    def turn(self) -> str:
        """
        the arm's lifting sense
        """
class BarrelRoller:
    """
    Barrel (cylindrical) cam with a translating roller follower: the roller's axis is radial and its carriage slides parallel to the cam axis; lift in m along the axis.
    """
    translating: typing.ClassVar[bool] = True
    type_name: typing.ClassVar[str] = 'barrel_roller'
    def __getstate__(self) -> tuple[float, float, float]:
        ...
    def __init__(self, cylinder_radius: typing.SupportsFloat | typing.SupportsIndex, groove_depth: typing.SupportsFloat | typing.SupportsIndex, roller_radius: typing.SupportsFloat | typing.SupportsIndex) -> None:
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
    def cylinder_radius(self) -> float:
        """
        outer radius R of the barrel cam (m, > 0)
        """
    @property
    def groove_depth(self) -> float:
        """
        depth d of the groove (m, 0 < d < R); the pitch radius is R - d/2
        """
    @property
    def roller_radius(self) -> float:
        """
        roller radius r_r (m, > 0)
        """
class BoundaryContinuity:
    """
    Continuity at one segment boundary: h, h', h'', h''' (m/rad^k) on each side,
    their jumps (right - left), the tolerances and the order through which the lift
    is continuous (-1: h jumps, ..., 3: C3 at least).
    """
    def __repr__(self) -> str:
        ...
    @property
    def continuous_through(self) -> int:
        """
        Highest k with h..h^(k) continuous: -1, 0, 1, 2 or 3 (3: C3 at least).
        """
    @property
    def jump(self) -> typing.Annotated[list[float], "FixedSize(4)"]:
        """
        right - left for h, h', h'', h''' (m/rad^k).
        """
    @property
    def left(self) -> typing.Annotated[list[float], "FixedSize(4)"]:
        """
        h, h', h'', h''' as the left segment ends.
        """
    @property
    def left_segment(self) -> int:
        """
        Index of the segment ending here.
        """
    @property
    def right(self) -> typing.Annotated[list[float], "FixedSize(4)"]:
        """
        h, h', h'', h''' as the right segment starts.
        """
    @property
    def right_segment(self) -> int:
        """
        Index of the segment starting here (0 at the wrap).
        """
    @property
    def theta(self) -> float:
        """
        Angle of the boundary (rad; the wrap at 0).
        """
    @property
    def tolerance(self) -> typing.Annotated[list[float], "FixedSize(4)"]:
        """
        Jumps up to these count as none (1e-6 of each derivative's scale).
        """
class ContinuityReport:
    """
    Continuity of a program at each segment boundary (the wrap at 360 deg last).
    """
    def __getitem__(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> BoundaryContinuity:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def boundaries(self) -> list[BoundaryContinuity]:
        """
        One BoundaryContinuity per segment end.
        """
    @property
    def continuous_through(self) -> int:
        """
        The program's order of continuity: the lowest over its boundaries.
        """
class MotionProgram:
    """
    Segments tiling one revolution; h(theta) and its theta-derivatives.
    """
    def complement(self, total: typing.SupportsFloat | typing.SupportsIndex) -> MotionProgram:
        """
        The conjugate program total - h(theta) (a conjugate pair's return cam), from the design lift (a
        profile error is not carried over); built-in laws only: a spline or polynomial segment is refused.
        """
    @staticmethod
    def from_table(theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], h: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], degree: typing.SupportsInt | typing.SupportsIndex = 5, smoothing: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> MotionProgram:
        """
        A whole revolution from a lift table, as one periodic B-spline segment. theta strictly increasing in
        [0, 2 pi) (rad), h in m. The table is NOT closed: the spline joins the last point to the first one
        revolution later (a repeated first point at theta[0] + 2 pi with the same h is dropped; with another
        h, refused). degree odd (1, 3, 5, 7; 5: C4); smoothing = lambda >= 0 (rad^degree): the fit minimizes
        sum (s(theta_i) - h_i)^2 + lambda * integral (s^(m))^2, m = (degree + 1) / 2; for N equally spaced
        points, harmonic k keeps 1 / (1 + lambda (2 pi / N) k^(2m)) of its amplitude.
        """
    @staticmethod
    def paper_default(total_rise: typing.SupportsFloat | typing.SupportsIndex = 0.01) -> MotionProgram:
        """
        Paper Table 1: dwell 0-30, modified-trapezoid rise 30-180, dwell 180-210, return 210-360 deg.
        """
    def __getstate__(self) -> tuple[list[Segment], typing.Any]:
        ...
    def __init__(self, segments: collections.abc.Sequence[Segment]) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def continuity(self) -> ContinuityReport:
        """
        Jumps of h, h', h'', h''' at every segment boundary (the wrap included) and the order through which
        the design lift is continuous there (a ContinuityReport).
        """
    def evaluate(self, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Lift h (m) and dh/dtheta, d2h/dtheta2, d3h/dtheta3 at theta (rad; scalar or array) as a dict.
        """
    def max_lift(self) -> float:
        """
        Largest lift over the revolution, profile error included (m).
        """
    def min_lift(self) -> float:
        """
        Smallest lift over the revolution, profile error included (m).
        """
    def require_continuity(self, order: typing.SupportsInt | typing.SupportsIndex) -> None:
        """
        Raise ValueError naming the first boundary (segments, angle in deg) where h .. h^(order) jumps;
        order 0 (lift), 1 (velocity), 2 (acceleration) or 3 (jerk).
        """
    def smoothness(self, excursions: typing.SupportsInt | typing.SupportsIndex = 5) -> dict:
        """
        Per-radian smoothness report as a dict: peaks {'velocity', 'acceleration', 'jerk'}: {'value' (m/rad^k),
        'theta' (rad)}; 'table_points'; 'residual' {'max', 'rms' (m), 'theta_of_max'} of the spline tables;
        'jerk_roughness' (RMS local jerk excursion / peak jerk: < 0.01 smooth, 0.1-0.5 noisy) and
        'jerk_excursions': the largest local excursions [{'theta', 'excursion' (m/rad^3)}], largest first.
        camfollower.motion.smoothness adds physical units at a speed.
        """
    def with_profile_error(self, error: ProfileError) -> MotionProgram:
        """
        A copy whose lift carries the cam's manufacturing error (replacing any it carries; ProfileError()
        removes it). It reaches evaluate, the contacts and the undercut / pressure-angle checks.
        """
    @property
    def profile_error(self) -> ProfileError | None:
        """
        The manufacturing error the lift carries, None for the design program.
        """
    @property
    def segments(self) -> list[Segment]:
        ...
class SpeedRamp:
    """
    A change of the camshaft's base speed to to_speed (rad/s, >= 0) over [start, start +
    duration] (s). shape 'smooth' (the acceleration rises and falls as 1 - cos: no step in it)
    or 'linear' (a constant acceleration, stepping at the ends).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, start: typing.SupportsFloat | typing.SupportsIndex, duration: typing.SupportsFloat | typing.SupportsIndex, to_speed: typing.SupportsFloat | typing.SupportsIndex, shape: str = 'smooth') -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def duration(self) -> float:
        """
        s
        """
    @property
    def shape(self) -> str:
        """
        'smooth' or 'linear'
        """
    @property
    def start(self) -> float:
        """
        s
        """
    @property
    def to_speed(self) -> float:
        """
        rad/s
        """
class SpeedModulation:
    """
    speed = base speed * (1 + amplitude sin(harmonic theta_base + phase)): amplitude in
    (-1, 1), harmonic a whole number of speed cycles per revolution, phase in rad.
    """
    def __getstate__(self) -> tuple[float, int, float]:
        ...
    def __init__(self, amplitude: typing.SupportsFloat | typing.SupportsIndex, harmonic: typing.SupportsInt | typing.SupportsIndex = 1, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def amplitude(self) -> float:
        ...
    @property
    def harmonic(self) -> int:
        ...
    @property
    def phase(self) -> float:
        """
        rad
        """
class SpeedProgram:
    """
    The camshaft's rotation over time: initial_speed (rad/s, >= 0), then the ramps in time order from t >= 0,
    and an optional modulation on top; angle 0 at t = 0. Closed-form angle, speed and acceleration.
    Give it to MechanismBuilder.speed_program: camshaft_speed becomes its nominal (highest base) speed,
    and changing that speed scales the whole program.
    """
    @staticmethod
    def constant(speed: typing.SupportsFloat | typing.SupportsIndex) -> SpeedProgram:
        """
        Turning at `speed` rad/s.
        """
    def __getstate__(self) -> tuple[float, list[SpeedRamp], SpeedModulation | None]:
        ...
    def __init__(self, initial_speed: typing.SupportsFloat | typing.SupportsIndex, ramps: collections.abc.Sequence[SpeedRamp] = [], modulation: SpeedModulation | None = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        The camshaft's angle (rad), speed (rad/s) and angular acceleration (rad/s^2) at t (s; scalar or
        array) as a dict.
        """
    def scaled_to(self, speed: typing.SupportsFloat | typing.SupportsIndex) -> SpeedProgram:
        """
        The same program with its base speeds scaled to the nominal speed `speed` (rad/s).
        """
    def time_at_angle(self, angle: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        The first time (s) the camshaft reaches `angle` (rad).
        """
    @property
    def constant_speed(self) -> bool:
        """
        turning at one speed all the time
        """
    @property
    def initial_speed(self) -> float:
        """
        rad/s
        """
    @property
    def modulation(self) -> SpeedModulation | None:
        ...
    @property
    def nominal_speed(self) -> float:
        """
        the highest base speed, rad/s
        """
    @property
    def periodic(self) -> bool:
        """
        the motion repeats every revolution (no ramps): a periodic steady state exists
        """
    @property
    def ramps(self) -> list[SpeedRamp]:
        ...
class Parameters:
    """
    The paper preset's parameters (SI units; paper Table 2 defaults; presets.paper(parameters)). Override any by keyword:
    Parameters(contact_stiffness=2e8, camshaft_speed_rpm=1000). Parameters.names() lists them.
    """
    @staticmethod
    def names() -> list[str]:
        ...
    def __init__(self, **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def get(self, name: str) -> typing.Any:
        """
        The value of one of names(): a float (SI units), or the contact_damping model's name.
        """
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
    def contact_damping(self) -> str:
        """
        contact damping model: 'none', 'hunt_crossley' or 'lankarani_nikravesh'; read-only: use replace(contact_damping=...)
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
class CouplerLinkage:
    """
    A cam-driven linkage in its own plane frame (m, rad): the swing arm (arm_dof, the follower's DOF) turning
    about arm_pivot, its pin at arm_length and at arm_angle when q = 0, lifting in the sense arm_turn; a
    coupler of coupler_length (m), coupler_mass (kg) and coupler_inertia about its mid-length (kg m^2); the
    output a 'slider' (output_dof in m along the line through output_origin at output_direction) or a
    'rocker' (output_dof in rad about the pivot output_origin, pin at output_length, positive in
    output_turn); branch +1/-1 picks the assembly. In a mechanism (MechanismBuilder.add_linkage) the coupler
    is a rigid body with DOFs <name>.x, <name>.y, <name>.angle joined to the two pins by pin joints
    <name>.input, <name>.output of joint_stiffness (N/m) and joint_damping (N s/m).
    """
    def __getstate__(self) -> tuple[str, str, str, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, float, str, float, float, float, str, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, float, str, int, float, float]:
        ...
    def __init__(self, name: str, arm_dof: str, output_dof: str, *, arm_pivot: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"] = ..., arm_length: typing.SupportsFloat | typing.SupportsIndex, arm_angle: typing.SupportsFloat | typing.SupportsIndex, arm_turn: ArmTurn | str = 'counter_clockwise', coupler_length: typing.SupportsFloat | typing.SupportsIndex, coupler_mass: typing.SupportsFloat | typing.SupportsIndex, coupler_inertia: typing.SupportsFloat | typing.SupportsIndex, output: str = 'slider', output_origin: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"] = ..., output_direction: typing.SupportsFloat | typing.SupportsIndex = 0.0, output_length: typing.SupportsFloat | typing.SupportsIndex = 0.0, output_turn: ArmTurn | str = 'counter_clockwise', branch: typing.SupportsInt | typing.SupportsIndex = 1, joint_stiffness: typing.SupportsFloat | typing.SupportsIndex, joint_damping: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def backward(self, wanted: MotionProgram, points: typing.SupportsInt | typing.SupportsIndex = 3600, degree: typing.SupportsInt | typing.SupportsIndex = 5) -> MotionProgram:
        """
        The backward solution: the arm's lift program (rad) that moves the output by `wanted` (its displacement
        from the reference, m or rad, per cam angle), from the inverse linkage at `points` equally spaced cam
        angles, fitted by a periodic B-spline of `degree` (MotionProgram.from_table).
        """
    def input_at(self, s: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        The arm's displacement (rad) that puts the output at s (the inverse of output_at).
        """
    def output_at(self, q: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        The rigid linkage's output displacement (m or rad from its reference) at the arm's displacement q (rad;
        scalar or array). Raises ValueError where the linkage cannot close.
        """
    def svaj(self, program: MotionProgram, theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        The output's displacement and its derivatives per radian of cam angle (s, ds, d2s, d3s) when the arm
        follows `program` (its lift, rad): exact (Taylor arithmetic through the closed-form linkage). Times
        omega^k for velocity, acceleration and jerk at a constant speed.
        """
    @property
    def arm_angle(self) -> float:
        """
        rad
        """
    @property
    def arm_dof(self) -> str:
        ...
    @property
    def arm_length(self) -> float:
        """
        m
        """
    @property
    def branch(self) -> int:
        ...
    @property
    def coupler_inertia(self) -> float:
        """
        kg m^2
        """
    @property
    def coupler_length(self) -> float:
        """
        m
        """
    @property
    def coupler_mass(self) -> float:
        """
        kg
        """
    @property
    def joint_damping(self) -> float:
        """
        N s/m
        """
    @property
    def joint_stiffness(self) -> float:
        """
        N/m
        """
    @property
    def name(self) -> str:
        ...
    @property
    def output(self) -> str:
        ...
    @property
    def output_dof(self) -> str:
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
    translating: typing.ClassVar[bool] = True
    type_name: typing.ClassVar[str] = 'translating_roller'
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
        """
        base circle radius r_b (m, > 0)
        """
    @property
    def offset(self) -> float:
        """
        lateral offset e of the axis (m, |e| < r_b + r_r)
        """
    @property
    def roller_radius(self) -> float:
        """
        roller radius r_r (m, > 0)
        """
class SolverSettings:
    """
    The integration settings of simulate(), simulate_many() and periodic_steady_state(), immutable
    (the C++ SolverSettings with its field names and defaults; docs/solvers.md).
    """
    FIELDS: typing.ClassVar[tuple]
    def __eq__(self, arg0: SolverSettings) -> bool:
        ...
    def __getstate__(self) -> dict:
        ...
    def __hash__(self) -> int:
        ...
    def __init__(self, method: typing.Any = 'newmark', **kwargs) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def fields(self) -> dict:
        """
        The fields that say what these settings are (method, time step, and the others that apply and
        differ from their defaults), as keywords of SolverSettings.
        """
    def replace(self, **kwargs) -> SolverSettings:
        ...
    @property
    def adaptive(self) -> bool:
        """
        True when a tolerance is set
        """
    @property
    def beta(self) -> float:
        ...
    @property
    def gamma(self) -> float:
        ...
    @property
    def hht_alpha(self) -> float:
        ...
    @property
    def increment_tolerance(self) -> float:
        ...
    @property
    def linear_solver(self) -> str:
        ...
    @property
    def max_halvings(self) -> int:
        ...
    @property
    def max_iterations(self) -> int:
        ...
    @property
    def max_step(self) -> float:
        ...
    @property
    def method(self) -> str:
        ...
    @property
    def residual_tolerance(self) -> float:
        ...
    @property
    def time_step(self) -> float:
        ...
    @property
    def tolerance(self) -> float | None:
        ...
class TranslatingFlat:
    """
    Translating flat-faced follower: face angle (rad) from the normal to the axis, offset (m).
    """
    translating: typing.ClassVar[bool] = True
    type_name: typing.ClassVar[str] = 'translating_flat'
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
        """
        base circle radius r_b (m, > 0)
        """
    @property
    def face_angle(self) -> float:
        """
        face angle g from the normal to the axis (rad, |g| < pi/2)
        """
    @property
    def offset(self) -> float:
        """
        lateral position e of the axis (m)
        """
class OscillatingRoller:
    """
    Oscillating (swing-arm) roller follower: pivot (x, y) in m in the ground frame, arm length (m); its lift program is the arm rotation in rad.
    """
    translating: typing.ClassVar[bool] = False
    type_name: typing.ClassVar[str] = 'oscillating_roller'
    def __getstate__(self) -> tuple[float, float, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, str]:
        ...
    def __init__(self, base_radius: typing.SupportsFloat | typing.SupportsIndex, roller_radius: typing.SupportsFloat | typing.SupportsIndex, pivot: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], arm_length: typing.SupportsFloat | typing.SupportsIndex, turn: ArmTurn | str = 'counter_clockwise') -> None:
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
    def arm_length(self) -> float:
        """
        pivot to roller centre L (m, > 0)
        """
    @property
    def base_radius(self) -> float:
        """
        base circle radius r_b (m, > 0)
        """
    @property
    def pivot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        arm pivot P (m, ground frame, outside the base circle)
        """
    @property
    def roller_radius(self) -> float:
        """
        roller radius r_r (m, > 0)
        """
    @property
    def start_angle(self) -> float:
        """
        start angle phi0 (rad, ground frame) of the arm at zero lift (a disk cam's: the roller on the base circle)
        """
    @property
    def turn(self) -> str:
        """
        the arm's lifting sense
        """
class OscillatingFlat:
    """
    Oscillating flat-faced follower: pivot (x, y) in m, face offset from the pivot (m); its lift program is the arm rotation in rad.
    """
    translating: typing.ClassVar[bool] = False
    type_name: typing.ClassVar[str] = 'oscillating_flat'
    def __getstate__(self) -> tuple[float, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"], float, str]:
        ...
    def __init__(self, base_radius: typing.SupportsFloat | typing.SupportsIndex, pivot: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], face_offset: typing.SupportsFloat | typing.SupportsIndex = 0.0, turn: ArmTurn | str = 'counter_clockwise') -> None:
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
        """
        base circle radius r_b (m, > 0)
        """
    @property
    def face_offset(self) -> float:
        """
        distance f of the face from the pivot (m, |r_b - f| < |P|)
        """
    @property
    def pivot(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        """
        arm pivot P (m, ground frame, outside the base circle)
        """
    @property
    def start_angle(self) -> float:
        """
        start angle phi0 (rad, ground frame) of the arm at zero lift (a disk cam's: the roller on the base circle)
        """
    @property
    def turn(self) -> str:
        """
        the arm's lifting sense
        """
class CamEccentricity:
    """
    An eccentric cam: its geometric centre at `radius` (m) from the bearing axis, in the direction `phase`
    (rad) of the cam frame, so at epsilon (cos(theta + phase), sin(theta + phase)) in the ground frame.
    formulation: 'exact' (the displaced profile's contact geometry; physical), or the paper's literal
    force K_h epsilon sin(theta + phase) on the camshaft, the roller or both ('paper_force_camshaft',
    'paper_force_roller', 'paper_force_both'; not physically derived, kept to reproduce the paper).
    unbalance_mass (kg): a rotating unbalance m epsilon omega^2 on the cam centre's DOFs.
    """
    def __getstate__(self) -> tuple[float, float, str, float]:
        ...
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0, formulation: str = 'exact', unbalance_mass: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def formulation(self) -> str:
        ...
    @property
    def phase(self) -> float:
        """
        rad
        """
    @property
    def radius(self) -> float:
        """
        m
        """
    @property
    def unbalance_mass(self) -> float:
        """
        kg
        """
class Groove:
    """
    A face groove (form closure) for a roller contact: the roller runs between the cam's inner flank (the
    contact's own surface) and an outer flank, the pitch curve's parallel at roller radius + clearance.
    clearance (m): groove width minus the roller's diameter, in (0, roller radius). The outer flank's Hertz
    law F = stiffness delta^exponent (1 + damping_factor delta'): the contact's own when stiffness is None
    (the outer flank is concave towards the roller: for the same material its stiffness is higher).
    """
    def __getstate__(self) -> tuple[float, typing.Any, float, float]:
        ...
    def __init__(self, clearance: typing.SupportsFloat | typing.SupportsIndex, *, stiffness: typing.SupportsFloat | typing.SupportsIndex | None = None, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def clearance(self) -> float:
        """
        m
        """
    @property
    def damping_factor(self) -> float:
        ...
    @property
    def exponent(self) -> float:
        ...
    @property
    def stiffness(self) -> typing.Any:
        """
        the outer flank's N/m^n, or None (the contact's law)
        """
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
    def add_bearing(self, name: str, shaft: str, at: typing.SupportsFloat | typing.SupportsIndex, *, stiffness: typing.SupportsFloat | typing.SupportsIndex, damping: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        A radial bearing at station `at` (m): spring-dampers (N/m, N s/m) from u_y and u_z to ground.
        """
    def add_clearance(self, name: str, gap: collections.abc.Sequence[tuple[str, typing.SupportsFloat | typing.SupportsIndex]], *, clearance: typing.SupportsFloat | typing.SupportsIndex, stiffness: typing.SupportsFloat | typing.SupportsIndex, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, friction: typing.SupportsFloat | typing.SupportsIndex = 0.0, sliding_dof: str = '', slip_velocity: typing.SupportsFloat | typing.SupportsIndex = 0.001) -> None:
        """
        A radial clearance: the gap coordinate u = sum c_j q_j (gap: [(dof, c_j), ...], m) is free for |u| <= clearance
        (m) and meets a wall law F = k delta^n (1 + chi delta') beyond; with friction > 0, regularized Coulomb
        friction mu F tanh(v / slip_velocity) on sliding_dof. Channels <name>.force, .side, .gap, .friction.
        """
    def add_conjugate_cams(self, name: str, program: MotionProgram, follower: typing.Any, return_follower: typing.Any, *, follower_dof: str, stiffness: typing.SupportsFloat | typing.SupportsIndex, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, backlash: typing.SupportsFloat | typing.SupportsIndex = 0.0, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0, return_program: MotionProgram | None = None, return_stiffness: typing.SupportsFloat | typing.SupportsIndex | None = None, return_exponent: typing.SupportsFloat | typing.SupportsIndex | None = None, return_damping_factor: typing.SupportsFloat | typing.SupportsIndex | None = None, cam_x: str = 'ground', cam_y: str = 'ground', lateral: str = 'ground', cam_twist: str = 'ground') -> None:
        """
        Conjugate cams: two cams on one shaft holding one follower both ways, the contacts '<name>.lift'
        (program, follower) and '<name>.return' (return_follower on the cam of return_program, by default the
        complement H - h with H the program's highest lift). A translating pair's return roller sits across
        the cam centre (its frame turned by pi, its offset measured in that frame); an oscillating pair's
        arms share the pivot and lift in opposite senses. backlash (m, or rad for an arm): the follower's play
        between the cams (> 0) or the interference that preloads them (< 0). return_*: the return contact's
        law where it differs.
        """
    def add_contact(self, name: str, program: MotionProgram, follower: typing.Any, *, follower_dof: str, stiffness: typing.SupportsFloat | typing.SupportsIndex, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0, cam_x: str = 'ground', cam_y: str = 'ground', lateral: str = 'ground', eccentricity: CamEccentricity | None = None, cam_twist: str = 'ground', groove: Groove | None = None, follower_ratio: typing.SupportsFloat | typing.SupportsIndex = 1.0, follower_offset: typing.SupportsFloat | typing.SupportsIndex = 0.0, frame_angle: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        A cam-follower contact pair: the cam's lift program (m, or rad for an oscillating follower), the follower
        type, the DOF of the follower's coordinate, a Hertz law F = k delta^n (1 + chi delta'), the cam's
        phase on the shaft (rad), the cam centre's DOFs, a translating follower's lateral DOF, an optional
        CamEccentricity, and the camshaft's twist DOF at the cam (rad; the cam angle is then omega t + phase +
        twist, a state, and the contact's moment loads the twist: channel <name>.cam_torque), and an optional
        Groove for a roller held between two flanks (channels <name>.penetration_rate, .outer_force,
        .outer_penetration, .outer_in_contact; event <name>.outer_contact). follower_ratio, follower_offset:
        the pair's follower coordinate is follower_offset + follower_ratio * q_follower (a second roller on
        one follower); frame_angle (rad): the pair's frame turned from the ground frame about the cam axis.
        """
    def add_damper(self, name: str, a: str, b: str = 'ground', *, damping: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def add_dof(self, name: str, mass: typing.SupportsFloat | typing.SupportsIndex, direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ...) -> None:
        """
        A DOF: mass (kg, or kg m^2 for a rotation) and, for a translation, its unit direction in space (for gravity).
        """
    def add_drive(self, name: str, shaft: str, at: typing.SupportsFloat | typing.SupportsIndex = 0.0, *, stiffness: typing.SupportsFloat | typing.SupportsIndex, damping: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        The drive as an imposed speed through a compliance: a torsional spring-damper (N m/rad, N m s/rad)
        from the twist at station `at` to the rigid rotation omega t.
        """
    def add_guide(self, name: str, lateral_dof: str, *, clearance: typing.SupportsFloat | typing.SupportsIndex, length: typing.SupportsFloat | typing.SupportsIndex, bushings: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], tilt_dof: str = '', tilt_reference: typing.SupportsFloat | typing.SupportsIndex = 0.0, stiffness: typing.SupportsFloat | typing.SupportsIndex, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, friction: typing.SupportsFloat | typing.SupportsIndex = 0.0, sliding_dof: str = '', slip_velocity: typing.SupportsFloat | typing.SupportsIndex = 0.001) -> None:
        """
        A rod in a guide of `length` (m) with one or two bushings at axial positions (m, in [0, length]); two
        bushings need the rod's tilt DOF (rad, about tilt_reference). One clearance per bushing
        (<name>, or <name>.bushing1/.bushing2).
        """
    def add_linkage(self, linkage: CouplerLinkage) -> None:
        """
        Add a CouplerLinkage: its coupler's DOFs <name>.x, <name>.y, <name>.angle and the pin joints
        <name>.input, <name>.output (channels .force, .stretch), assembled at q = 0.
        """
    def add_load(self, dof: str, force: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Constant load along +q (N).
        """
    def add_mass(self, dof: str, mass: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        A lumped mass (kg) or inertia (kg m^2) added to a DOF (e.g. a flywheel on a shaft's twist).
        """
    def add_motor(self, name: str, shaft: str, at: typing.SupportsFloat | typing.SupportsIndex = 0.0, *, inertia: typing.SupportsFloat | typing.SupportsIndex, position_gain: typing.SupportsFloat | typing.SupportsIndex, velocity_gain: typing.SupportsFloat | typing.SupportsIndex = 0.0, torque: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        The drive as a speed-controlled motor with a flywheel at `at`: inertia (kg m^2) on the twist, the
        controller's position gain (N m/rad, > 0) and velocity gain (N m s/rad) to the nominal rotation, and
        a constant forward torque (N m, e.g. the cams' mean torque as feed-forward).
        """
    def add_shaft(self, name: str, *, length: typing.SupportsFloat | typing.SupportsIndex, outer_diameter: typing.SupportsFloat | typing.SupportsIndex, inner_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.0, stations: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] = [], max_element_length: typing.SupportsFloat | typing.SupportsIndex = 0.0, youngs_modulus: typing.SupportsFloat | typing.SupportsIndex = 210000000000.0, poisson_ratio: typing.SupportsFloat | typing.SupportsIndex = 0.3, density: typing.SupportsFloat | typing.SupportsIndex = 7850.0, axial: bool = False, damping: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        A flexible shaft along x from 0 to `length` (m): Timoshenko beam elements (bending in two planes with
        shear and rotary inertia, torsion; axial if asked) of a solid or hollow circular steel section (SI
        units). Every station (m) where a cam, bearing, drive or mass will sit must be listed; no element is
        longer than max_element_length (0: one element between stations). Node DOFs are named
        '<name>.<node>.<uy|uz|rx|ry|rz>' (shaft_dof()); the twist rx is relative to the rigid rotation.
        damping (s): material damping C = damping K of the shaft's elements (mode ratio damping omega / 2).
        """
    def add_spring(self, name: str, a: str, b: str = 'ground', *, stiffness: typing.SupportsFloat | typing.SupportsIndex, damping: typing.SupportsFloat | typing.SupportsIndex = 0.0, preload: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        """
        Spring-damper between DOFs a and b (or 'ground'); force on a: -(preload + k (q_a - q_b) + c (v_a - v_b)).
        """
    def add_spring_chain(self, name: str, a: str, b: str = 'ground', *, stiffness: typing.SupportsFloat | typing.SupportsIndex, mass: typing.SupportsFloat | typing.SupportsIndex, elements: typing.SupportsInt | typing.SupportsIndex = 6, damping: typing.SupportsFloat | typing.SupportsIndex = 0.0, preload: typing.SupportsFloat | typing.SupportsIndex = 0.0, direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = ...) -> None:
        """
        A spring with its own mass (a valve spring that surges): `elements` equal springs in series with
        interior masses '<name>.1', ...; its surge frequencies tend to (j / 2) sqrt(stiffness / mass) with both
        ends held. stiffness, damping and preload are the whole spring's.
        """
    def build(self) -> ...:
        """
        Validate and assemble the immutable Mechanism.
        """
    def mount_cam(self, name: str, program: MotionProgram, follower: typing.Any, *, follower_dof: str, shaft: str, at: typing.SupportsFloat | typing.SupportsIndex, stiffness: typing.SupportsFloat | typing.SupportsIndex, exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0, width: typing.SupportsFloat | typing.SupportsIndex = 0.0, cam_mass: typing.SupportsFloat | typing.SupportsIndex = 0.0, cam_inertia: typing.SupportsFloat | typing.SupportsIndex = 0.0, lateral: str = 'ground') -> None:
        """
        A contact pair whose cam sits on a shaft at station `at` (m): the cam centre is the node's (u_y, u_z), its
        angle omega t + phase + the node's twist. Its contact frame has x along the global y and the follower's
        axis along the global z (a barrel cam's: x along the global y, its follower's axis along the shaft, so
        the cam centre is the node's (u_y, u_x) and the shaft needs axial=True). width (m) is checked against
        the other cams; cam_mass (kg) and cam_inertia (kg m^2) are added to the node.
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
    def shaft_dof(self, shaft: str, at: typing.SupportsFloat | typing.SupportsIndex, dof: str) -> str:
        """
        The DOF name of a shaft's node at station `at` (m).
        """
    @property
    def camshaft_speed_rpm(self) -> float:
        """
        The camshaft speed, rpm (with a speed program its nominal speed: setting it scales the program).
        """
    @camshaft_speed_rpm.setter
    def camshaft_speed_rpm(self, arg1: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def dof_names(self) -> list[str]:
        ...
    @property
    def clearances(self) -> list:
        """
        Clearances, as dicts with add_clearance's parameters.
        """
    @property
    def contacts(self) -> list:
        """
        Cam-follower contacts, as dicts with add_contact's parameters (name, program, follower, stiffness, exponent, damping_factor, phase, cam_x, cam_y, follower_dof, lateral, eccentricity, cam_twist, groove) and paper_backlash (backlash, switch_width, guide_dof, guide_stiffness).
        """
    @property
    def dofs(self) -> list:
        """
        DOFs in order, as dicts (name, mass, direction); a shaft's DOFs as one dict describing the shaft, a linkage's coupler DOFs as one dict naming the linkage.
        """
    @property
    def linkages(self) -> list[CouplerLinkage]:
        """
        The linkages added, in order.
        """
    @property
    def loads(self) -> list:
        """
        Constant loads, as dicts (dof, force).
        """
    @property
    def masses(self) -> list:
        """
        Point masses added to DOFs, as (dof, mass) tuples (kg).
        """
    @property
    def speed_program(self) -> SpeedProgram | None:
        """
        A variable camshaft speed (SpeedProgram), or None: constant camshaft_speed_rpm. Setting one makes its
        nominal speed the camshaft speed.
        """
    @speed_program.setter
    def speed_program(self, arg1: SpeedProgram | None) -> None:
        ...
    @property
    def springs(self) -> list:
        """
        Springs and dampers, as dicts (name, a, b, stiffness, damping, preload).
        """
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
    def lowest_modes(self, theta: typing.SupportsFloat | typing.SupportsIndex = 0.0, count: typing.SupportsInt | typing.SupportsIndex = 0) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]]:
        """
        (frequencies in Hz ascending, mass-normalized mode shapes as columns) of the lowest `count` modes at
        camshaft angle theta (rad), contacts linearized; count = 0: all (a dense solve). A few of a large
        model (above 200 DOFs, a flexible camshaft): shift-invert Lanczos on the sparse factor (Spectra).
        """
    def modal_analysis(self, theta: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> dict:
        """
        Undamped natural frequencies (Hz, ascending), mass-normalized mode shapes and the tangent stiffness at
        the quasi-static equilibrium at camshaft angle theta (rad), contacts linearized: every mode, as
        lowest_modes(theta) (the one modal analysis).
        """
    def quasi_static_path(self, dof: str, theta: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], angles: typing.SupportsInt | typing.SupportsIndex = 720) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The DOF's static equilibrium at the shaft angles theta (rad, in [0, 2 pi]): solved at `angles`
        equally spaced angles (default every 0.5 deg) and interpolated periodically, or with angles = 0 at
        every theta (synthesis/lift_samples.hpp). RuntimeError where the mechanism has no static equilibrium.
        """
    def static_equilibrium(self, theta: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Quasi-static equilibrium at camshaft angle theta (rad).
        """
    def step_limit(self, beta: typing.SupportsFloat | typing.SupportsIndex) -> dict:
        """
        Largest stable time step (s) of Newmark with gamma = 1/2 and this beta in [0, 1/4] at the
        quasi-static equilibrium at t = 0 (contacts linearized), with the solver's 10 % margin, and the mode
        that sets it (frequency_hz, damping_ratio); +inf at beta = 1/4. Below 1/4 the velocity is processed
        to fourth order, and damping lowers the limit (docs/solvers.md). A fixed step above it is refused.
        """
    def with_camshaft_speed_rpm(self, rpm: typing.SupportsFloat | typing.SupportsIndex) -> Mechanism:
        """
        The same mechanism at another camshaft speed (a new object).
        """
    @property
    def camshaft_speed_rpm(self) -> float:
        ...
    @property
    def clearance_names(self) -> list[str]:
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
    def follower_dofs(self) -> list[str]:
        """
        the follower DOF of each contact
        """
    @property
    def initial_state(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        static equilibrium at t = 0 (m or rad per DOF)
        """
    @property
    def initial_velocity(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        quasi-static velocity at t = 0 (the rate of the static equilibrium as the cam turns)
        """
    @property
    def mass(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def omega(self) -> float:
        """
        camshaft speed, rad/s (with a speed program its nominal speed)
        """
    @property
    def period(self) -> float:
        """
        one camshaft revolution at omega, s
        """
    @property
    def periodic(self) -> bool:
        """
        The motion repeats every period (no speed ramps): settling and the periodic steady state apply.
        """
    @property
    def speed_program(self) -> SpeedProgram:
        """
        The camshaft's rotation (a SpeedProgram; constant at omega without a speed program).
        """
    @property
    def size(self) -> int:
        ...
    @property
    def stiffness(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def warnings(self) -> list[str]:
        """
        what the formulation warns about (also issued as UserWarning when built)
        """
class Elastic:
    """
    Elastic constants of one body: Young's modulus (Pa) and Poisson's ratio.
    """
    @staticmethod
    def effective_modulus(a: Elastic, b: Elastic) -> float:
        """
        Contact modulus E* (Pa): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
        """
    @staticmethod
    def steel() -> Elastic:
        """
        E = 210 GPa, nu = 0.3.
        """
    def __init__(self, youngs_modulus: typing.SupportsFloat | typing.SupportsIndex = 210000000000.0, poisson_ratio: typing.SupportsFloat | typing.SupportsIndex = 0.3) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def poisson_ratio(self) -> float:
        """
        Poisson's ratio nu, [0, 0.5)
        """
    @property
    def youngs_modulus(self) -> float:
        """
        Young's modulus E (Pa)
        """
class LineContact:
    """
    Hertz contact of a roller of width `length` (m) on the cam: straight (line contact, Johnson ch. 4) or crowned with crown_radius (m; elliptical contact, Hamrock-Brewe fits, made for radius ratios 1 to 100).
    """
    @staticmethod
    def palmgren_law(length: typing.SupportsFloat | typing.SupportsIndex, damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> dict:
        """
        Palmgren's steel roller law F = K delta^(10/9) for roller width `length` (m): dict with
        stiffness (N/m^(10/9)), exponent (10/9), damping_factor (s/m), the keys of a contact law.
        """
    def __init__(self, length: typing.SupportsFloat | typing.SupportsIndex, roller: Elastic = ..., cam: Elastic = ..., crown_radius: typing.SupportsFloat | typing.SupportsIndex = ...) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def profile_stress(self, follower: typing.Any, program: MotionProgram, force: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], theta: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Contact stress along the cam at theta (rad, scalar or array) for force (N, scalar or one per
        angle). The roller radius is the follower's (a flat face is a plane). Keys: half_width (m),
        max_pressure (Pa), effective_radius (m), surface_radius (m, the cam's, signed). A crowned
        roller whose radius ratio leaves the fits' range 1 to 100 at some angles: one UserWarning.
        """
    def stress(self, force: typing.SupportsFloat | typing.SupportsIndex, radius: typing.SupportsFloat | typing.SupportsIndex, cam_radius: typing.SupportsFloat | typing.SupportsIndex = ...) -> dict:
        """
        Contact stress for a normal force (N) between the roller of radius `radius` and a cam of
        radius cam_radius (m; > 0 convex, < 0 concave, inf flat). Keys: half_width (m, along the
        rolling direction), max_pressure (Pa), effective_radius (m); crowned also a (semi-axis
        across the width), b (= half_width), approach (m) and radius_ratio (crown radius over the
        rolling radius, or its inverse: >= 1). The crowned values come from Hamrock-Brewe fits made
        for radius ratios 1 to 100, within 5.4 % of exact Hertz there; beyond 100 (a long crown on a
        small roller) they drift (a +6.9 % at 200, +15 % at 1000) and a UserWarning says so.
        """
    @property
    def cam(self) -> Elastic:
        ...
    @property
    def crown_radius(self) -> float:
        """
        crown radius (m); inf: straight roller
        """
    @property
    def crowned(self) -> bool:
        ...
    @property
    def effective_modulus(self) -> float:
        """
        contact modulus E* (Pa)
        """
    @property
    def length(self) -> float:
        """
        roller width L (m)
        """
    @property
    def roller(self) -> Elastic:
        ...
def _case_from_dict(data: dict, origin: str, base_dir: str) -> dict:
    ...
def _force_closure(builder: MechanismBuilder, rpm: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> dict:
    ...
def _lift_samples(system: Mechanism, contact: str, output: str, objective: str, theta: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], q: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], acceleration: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], force: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], dwells_of: MotionProgram | None = None) -> dict:
    """
    Internal: camfollower.synthesis reduces a recorded revolution with this (synthesis/lift_samples.hpp).
    """
def _parse_toml(text: bytes, origin: str) -> dict:
    ...
def _read_config(text: bytes, origin: str, base_dir: str) -> tuple:
    ...
def _toml_line(text: bytes, path: list) -> int | None:
    ...
def _run(system: Mechanism, settings: SolverSettings, duration: typing.SupportsFloat | typing.SupportsIndex, decimation: typing.SupportsInt | typing.SupportsIndex, record_from: typing.SupportsFloat | typing.SupportsIndex, max_output_bytes: typing.SupportsFloat | typing.SupportsIndex, progress: typing.Any, progress_interval: typing.SupportsFloat | typing.SupportsIndex, settle_period: typing.SupportsFloat | typing.SupportsIndex | None = None, settle_dofs: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] = [], settle_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001, settle_min_revolutions: typing.SupportsInt | typing.SupportsIndex = 2, settle_max_revolutions: typing.SupportsInt | typing.SupportsIndex = 200, q0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"] | None = None, v0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"] | None = None) -> dict:
    """
    Internal: camfollower.simulate() calls this and wraps the output in a Result.
    """
def _run_many(cases: list, settings: SolverSettings, decimation: typing.SupportsInt | typing.SupportsIndex, max_output_bytes: typing.SupportsFloat | typing.SupportsIndex, threads: typing.SupportsInt | typing.SupportsIndex, progress: typing.Any, progress_interval: typing.SupportsFloat | typing.SupportsIndex, settle_tolerance: typing.SupportsFloat | typing.SupportsIndex, settle_min_revolutions: typing.SupportsInt | typing.SupportsIndex, settle_max_revolutions: typing.SupportsInt | typing.SupportsIndex) -> list:
    """
    Internal: camfollower.simulate_many() calls this with (system, duration, record_from, settle_period,
    settle_dofs) per case and wraps each output in a Result.
    """
def _shoot(system: Mechanism, settings: SolverSettings, period: typing.SupportsFloat | typing.SupportsIndex | None, start_time: typing.SupportsFloat | typing.SupportsIndex, tolerance: typing.SupportsFloat | typing.SupportsIndex, shooting_max_iterations: typing.SupportsInt | typing.SupportsIndex, warmup_revolutions: typing.SupportsInt | typing.SupportsIndex, perturbation: typing.SupportsFloat | typing.SupportsIndex, multipliers: bool, monodromy: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"] | None, q0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"] | None, v0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"] | None, monodromy_method: str = "auto") -> dict:
    """
    Internal: camfollower.periodic_steady_state() calls this and wraps the output in a PeriodicOrbit.
    """
def barrel_groove(follower: typing.Any, program: MotionProgram, points: typing.SupportsInt | typing.SupportsIndex = 3600, clearance: typing.SupportsFloat | typing.SupportsIndex = 0.0, roller: str = 'cylindrical') -> dict:
    """
    A barrel cam's groove (BarrelRoller or BarrelArmRoller) at theta_k = 2 pi k / points, SI units: the exact
    walls (envelopes of the roller's positions) for a 'cylindrical' or the ideal 'tapered' roller at the
    radii (top, pitch, bottom). Keys: theta, radii (m), centre_angle/centre_z (roller centre at the pitch
    radius: position round the cam in rad, the roller's station being at theta, and height in m), lift_angle,
    lift_z, back_angle, back_z (3 x points: the lifting flank and the opposite one, clearance m away),
    pressure_angle (3 x points, rad, on the lifting flank), cutter_cross/cutter_axial/cutter_plunge (m: the
    4-axis machining path of a cutter shaped as the roller, larger by clearance/2), clearance, roller.
    Raises ValueError naming the radius and angle where the roller undercuts or jams.
    """
def cam_outline(follower: typing.Any, program: MotionProgram, points: typing.SupportsInt | typing.SupportsIndex = 3600, cutter_radius: typing.SupportsFloat | typing.SupportsIndex | None = None, unit: str = 'mm') -> dict:
    """
    Cam surface over one revolution (theta_k = 2 pi k / points, cam frame, lengths in `unit`), its outward unit
    normals, and the cutter-centre path for cutter_radius (m; the surface offset outward by it). Keys: theta,
    surface_x/y, normal_x/y, cutter_x/y (with a cutter), unit, cutter_radius, notes (the file header lines).
    Raises ValueError on undercut, or a cutter larger than the tightest concave radius (named with its angle).
    """
def check_output_target(path: str, protect: collections.abc.Sequence[str] = []) -> None:
    """
    Raise ValueError if write_file_atomically would refuse `path` (checked before a long run).
    """
def length_units() -> dict:
    """
    Length units accepted by the exports: {name: metres per unit} (m, mm, um, inch = 0.0254 m).
    """
def paper_preset(parameters: Parameters | None = None, program: MotionProgram | None = None, *, eccentricity: CamEccentricity | None = None, guide_clearance: typing.SupportsFloat | typing.SupportsIndex = 0.0, guide_wall_damping_factor: typing.SupportsFloat | typing.SupportsIndex = 0.0, guide_friction: typing.SupportsFloat | typing.SupportsIndex = 0.0, element_damping_ratio: typing.SupportsFloat | typing.SupportsIndex = 0.0, paper_backlash: typing.SupportsFloat | typing.SupportsIndex = 0.0, paper_backlash_switch_width: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> Mechanism:
    """
    The paper's 7-DOF model (Tounsi et al.) built from the mechanism parts; DOFs y1..y4, x1..x3,
    contact 'cam'. parameters: a Parameters (Table 2 defaults). Options: a CamEccentricity;
    guide_clearance (m, radial) > 0 puts the rod x3 in a gap with walls of stiffness K_rb (clearance
    'guide'; wall damping factor chi in s/m, Coulomb friction on y3); element_damping_ratio in (0, 1)
    puts a damper on every element (springs, contact, guide walls) at that ratio of its own critical
    damping, in place of the paper's few dampers. paper_backlash (m) > 0: the paper's literal backlash, the
    rod's side imposed by the program (offset e +- b, K_rb anchored on the displaced rod), its switch
    ramped over paper_backlash_switch_width (rad; 0: hard).
    """
def valve_train_parameter_units() -> dict:
    """
    The valve-train preset's real-valued parameters and their SI units.
    """
def valve_train_preset(engine_speed_rpm: typing.SupportsFloat | typing.SupportsIndex, parameters: dict) -> Mechanism:
    """
    Internal: camfollower.presets.valve_train() calls this.
    """
def write_barrel_groove_csv(path: str, follower: typing.Any, program: MotionProgram, points: typing.SupportsInt | typing.SupportsIndex = 3600, clearance: typing.SupportsFloat | typing.SupportsIndex = 0.0, roller: str = 'cylindrical', unit: str = 'mm') -> None:
    """
    Write a barrel cam's groove as CSV, atomically: commented header (units, frame, radii, roller, machining
    axes), then per cam angle the roller centre, both flanks and the pressure angle at the top, pitch and
    bottom radii (angles in deg, lengths in `unit`) and the machining path.
    """
def write_cam_csv(path: str, follower: typing.Any, program: MotionProgram, points: typing.SupportsInt | typing.SupportsIndex = 3600, cutter_radius: typing.SupportsFloat | typing.SupportsIndex | None = None, unit: str = 'mm') -> None:
    """
    Write the cam outline as CSV (commented header with units, rotation, zero reference, follower, cutter,
    points; then theta_rad,surface_x_<unit>,surface_y_<unit>[,cutter_x_<unit>,cutter_y_<unit>]), atomically.
    """
def write_file_atomically(path: str, content: bytes, protect: collections.abc.Sequence[str] = []) -> None:
    """
    Replace or create `path` with `content` (bytes) atomically: a uniquely named temporary in the same
    folder, then a rename; nothing is left behind on failure. Refuses (ValueError) a target that is a
    directory, FIFO, socket, device or symbolic link, a read-only file, a path holding a NUL, and any
    of `protect` (input files the run read).
    """
MAX_CAMSHAFT_SPEED: float = 100000.0
MAX_PART_LENGTH: float = 1000.0
MAX_POINTS: int = 10000000
METHODS: dict  # name -> (order, summary), from the C++ method table
MIN_CAMSHAFT_SPEED: float = 1e-06
RUNGE_KUTTA_DEFAULT_TOLERANCE: float = 1e-06
SHOOTING_MAX_STATE_SIZE: int = 400  # 2n: the largest state shooting's dense monodromy takes
SPARSE_BACKEND_THRESHOLD: int = 100  # DOFs from which linear_solver 'auto' runs the sparse backend
__version__: str = '0.1.0'
realistic_damping_ratio: float = 0.03
