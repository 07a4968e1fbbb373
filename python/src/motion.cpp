// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/motion: laws, profile errors and programs.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/motion/profile_error.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/motion/smoothness.hpp"

namespace camfollower::python {

namespace {
std::vector<double> to_vector(const DoubleArray& a, const char* name) {
    if (a.ndim() > 1) detail::fail(name, " must be one-dimensional, got ", a.ndim(), " dimensions");
    return std::vector<double>(a.data(), a.data() + a.size());
}

// A custom law's defining data as a dict (its pickled form, rebuilt through the validating factories);
// None for a built-in law.
py::object law_definition(const MotionLaw& law) {
    if (const LiftSpline* s = law.spline())
        return py::dict(py::arg("periodic") = s->is_periodic(), py::arg("theta") = s->theta(), py::arg("h") = s->h(),
                        py::arg("degree") = s->degree(), py::arg("smoothing") = s->smoothing(),
                        py::arg("start_derivatives") = s->start_derivatives(),
                        py::arg("end_derivatives") = s->end_derivatives());
    if (const LiftPolynomial* p = law.polynomial())
        return py::dict(py::arg("theta_start") = p->theta_start(), py::arg("theta_end") = p->theta_end(),
                        py::arg("start") = p->start(), py::arg("end") = p->end(), py::arg("interior") = p->interior(),
                        py::arg("coefficients") = p->coefficients());
    return py::none();
}

MotionLaw custom_law_from(LawKind kind, const py::dict& d) {
    if (kind == LawKind::spline) {
        const SplineOptions options{d["degree"].cast<int>(), d["smoothing"].cast<double>()};
        auto theta = d["theta"].cast<std::vector<double>>();
        auto h = d["h"].cast<std::vector<double>>();
        if (d["periodic"].cast<bool>())
            return MotionLaw::from_spline(std::make_shared<const LiftSpline>(LiftSpline::periodic(theta, h, options)));
        return MotionLaw::from_spline(std::make_shared<const LiftSpline>(
            LiftSpline::segment(theta, h, options, d["start_derivatives"].cast<std::vector<double>>(),
                                d["end_derivatives"].cast<std::vector<double>>())));
    }
    return MotionLaw::from_polynomial(std::make_shared<const LiftPolynomial>(LiftPolynomial::from_conditions(
        d["theta_start"].cast<double>(), d["theta_end"].cast<double>(), d["start"].cast<std::vector<double>>(),
        d["end"].cast<std::vector<double>>(), d["interior"].cast<std::vector<std::pair<double, double>>>())));
}

py::tuple law_state(const MotionLaw& law) {
    if (law.is_custom()) return py::make_tuple(int(law.kind()), law_definition(law));
    return py::make_tuple(int(law.kind()), law.b(), law.c(), law.d());
}

py::dict peaks_dict(const LiftPeaks& p) {
    const auto one = [](const LiftPeak& q) { return py::dict(py::arg("value") = q.value, py::arg("theta") = q.theta); };
    return py::dict(py::arg("velocity") = one(p.velocity), py::arg("acceleration") = one(p.acceleration),
                    py::arg("jerk") = one(p.jerk));
}

py::dict smoothness_dict(const SmoothnessReport& r) {
    py::list excursions;
    for (const JerkExcursion& e : r.jerk_excursions)
        excursions.append(py::dict(py::arg("theta") = e.theta, py::arg("excursion") = e.excursion));
    py::dict d = peaks_dict(r.peaks);
    d["table_points"] = r.table_points;
    d["residual"] = py::dict(py::arg("max") = r.residual.max, py::arg("rms") = r.residual.rms,
                             py::arg("theta_of_max") = r.residual.theta_of_max);
    d["jerk_roughness"] = r.jerk_roughness;
    d["jerk_excursions"] = excursions;
    return d;
}

py::dict motion_dict(const DoubleArray& theta, const std::function<FollowerMotion(double)>& f) {
    return map_to_dict<4>(theta, {"h", "dh", "d2h", "d3h"}, [&](double t) {
        const FollowerMotion v = f(t);
        return std::array<double, 4>{v.h, v.dh, v.d2h, v.d3h};
    });
}

MotionLaw law_from(const py::tuple& t) {
    const LawKind kind = LawKind(t[0].cast<int>());
    if (kind == LawKind::spline || kind == LawKind::polynomial) return custom_law_from(kind, t[1].cast<py::dict>());
    switch (kind) {
        case LawKind::dwell: return MotionLaw::dwell();
        case LawKind::simple_harmonic: return MotionLaw::simple_harmonic();
        case LawKind::cycloidal: return MotionLaw::cycloidal();
        case LawKind::polynomial_345: return MotionLaw::polynomial_345();
        case LawKind::polynomial_4567: return MotionLaw::polynomial_4567();
        case LawKind::constant_acceleration: return MotionLaw::constant_acceleration();
        case LawKind::sine_constant_cosine:
            return MotionLaw::sine_constant_cosine(t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>());
        case LawKind::spline:
        case LawKind::polynomial: break;
    }
    detail::fail("MotionLaw: invalid pickled state");
}

// One component as a dict: {"kind": "waviness" | "dent" | "fourier", its parameters}. Also the
// pickled form, rebuilt through the validating constructors.
py::dict component_dict(const ProfileError::Component& c) {
    if (const auto* w = std::get_if<ProfileError::Waviness>(&c))
        return py::dict(py::arg("kind") = "waviness", py::arg("amplitude") = w->amplitude, py::arg("order") = w->order,
                        py::arg("phase") = w->phase);
    if (const auto* d = std::get_if<ProfileError::Dent>(&c))
        return py::dict(py::arg("kind") = "dent", py::arg("centre") = d->centre, py::arg("width") = d->width,
                        py::arg("depth") = d->depth);
    const auto& f = std::get<ProfileError::Fourier>(c);
    return py::dict(py::arg("kind") = "fourier", py::arg("mean") = f.mean, py::arg("cos") = f.cos,
                    py::arg("sin") = f.sin);
}

ProfileError component_from(const py::dict& d) {
    const std::string kind = d["kind"].cast<std::string>();
    if (kind == "waviness")
        return ProfileError::waviness(d["amplitude"].cast<double>(), d["order"].cast<int>(), d["phase"].cast<double>());
    if (kind == "dent")
        return ProfileError::dent(d["centre"].cast<double>(), d["width"].cast<double>(), d["depth"].cast<double>());
    if (kind == "fourier")
        return ProfileError::fourier(d["mean"].cast<double>(), d["cos"].cast<std::vector<double>>(),
                                     d["sin"].cast<std::vector<double>>());
    detail::fail("ProfileError: invalid pickled component kind '", kind, "'");
}

py::tuple error_state(const ProfileError& e) {
    py::list out;
    for (const auto& c : e.components()) out.append(component_dict(c));
    return py::tuple(out);
}

ProfileError error_from(const py::tuple& t) {
    ProfileError sum;
    for (const py::handle& c : t) sum = sum + component_from(c.cast<py::dict>());
    return sum;
}

std::string error_repr(const ProfileError& e) {
    std::string out = "ProfileError(";
    for (std::size_t i = 0; i < e.components().size(); ++i) {
        const auto& c = e.components()[i];
        if (i) out += " + ";
        if (const auto* w = std::get_if<ProfileError::Waviness>(&c))
            out += detail::concat("waviness(amplitude=", w->amplitude, ", order=", w->order, ", phase=", w->phase, ")");
        else if (const auto* d = std::get_if<ProfileError::Dent>(&c))
            out += detail::concat("dent(centre=", d->centre, ", width=", d->width, ", depth=", d->depth, ")");
        else out += detail::concat("fourier(", std::get<ProfileError::Fourier>(c).cos.size(), " harmonics)");
    }
    return out + ")";
}
}  // namespace

void bind_motion(py::module_& m) {
    py::class_<PeakCoefficients>(m, "PeakCoefficients", "Peaks of |V|, |A|, |J| of a normalized law.")
        .def_readonly("velocity", &PeakCoefficients::velocity)
        .def_readonly("acceleration", &PeakCoefficients::acceleration)
        .def_readonly("jerk", &PeakCoefficients::jerk)
        .def("__repr__", [](const PeakCoefficients& p) {
            return detail::concat("PeakCoefficients(velocity=", p.velocity, ", acceleration=", p.acceleration,
                                  ", jerk=", p.jerk, ")");
        });

    py::class_<MotionLaw>(
        m, "MotionLaw",
        "Normalized motion law S(x) on x in [0, 1], S(0) = 0, S(1) = 1. Build one with a "
        "static method (MotionLaw.modified_trapezoid(), ...).\n"
        "A user-defined law (a lift table as a spline, a polynomial from boundary conditions) comes\n"
        "from Segment.from_table / Segment.polynomial / MotionProgram.from_table; it holds its lift in\n"
        "m relative to its segment's start (evaluate_lift), and evaluate/peaks give the normalized\n"
        "form only when its net lift is not zero.")
        .def_static("dwell", &MotionLaw::dwell)
        .def_static("simple_harmonic", &MotionLaw::simple_harmonic)
        .def_static("cycloidal", &MotionLaw::cycloidal)
        .def_static("modified_trapezoid", &MotionLaw::modified_trapezoid)
        .def_static("modified_sine", &MotionLaw::modified_sine)
        .def_static("polynomial_345", &MotionLaw::polynomial_345)
        .def_static("polynomial_4567", &MotionLaw::polynomial_4567)
        .def_static("constant_acceleration", &MotionLaw::constant_acceleration)
        .def_static("sine_constant_cosine", &MotionLaw::sine_constant_cosine, py::arg("b"), py::arg("c"), py::arg("d"),
                    "Sine-constant-cosine acceleration family; b + c + d = 1 (fractions of the segment).")
        .def_property_readonly("name", &MotionLaw::name)
        .def_property_readonly("b", &MotionLaw::b)
        .def_property_readonly("c", &MotionLaw::c)
        .def_property_readonly("d", &MotionLaw::d)
        .def("peaks", &MotionLaw::peaks,
             "Peak coefficients C_v, C_a, C_j. For a spline / polynomial law: found numerically, normalized by its\n"
             "span beta and net lift L (C_a = max|h''| beta^2 / |L|; inf when L = 0).")
        .def_property_readonly("is_custom", &MotionLaw::is_custom, "True for a spline or polynomial law.")
        .def_property_readonly("definition", &law_definition,
                               "A spline / polynomial law's defining data as a dict (table, degree, smoothing, end\n"
                               "derivatives; or span, end conditions, interior points, coefficients in x); None\n"
                               "for a built-in law.")
        .def("has_zero_end_acceleration", &MotionLaw::has_zero_end_acceleration,
             "Whether S, V, A are continuous at both ends against a dwell (A = 0 at both ends, the law C2).")
        .def(
            "evaluate_lift",
            [](const MotionLaw& law, const DoubleArray& u) {
                return motion_dict(u, [&](double v) { return law.evaluate_lift(v); });
            },
            py::arg("u"),
            "A spline / polynomial law's lift relative to its segment start, h(theta_start + u) - h(theta_start)\n"
            "(m) and its derivatives dh, d2h, d3h (m/rad^k), u in [0, span] rad (scalar or array), as a dict.")
        .def(
            "lift_peaks", [](const MotionLaw& law) { return peaks_dict(law.lift_peaks()); },
            "A spline / polynomial law's peaks of |h'|, |h''|, |h'''| (m/rad^k) and their angles as offsets from\n"
            "the segment start (rad): {'velocity': {'value', 'theta'}, 'acceleration': ..., 'jerk': ...}.")
        .def(
            "evaluate",
            [](const MotionLaw& law, const DoubleArray& x) {
                return map_to_dict<4>(x, {"S", "V", "A", "J"}, [&](double xi) {
                    const LawValue v = law.evaluate(xi);
                    return std::array<double, 4>{v.S, v.V, v.A, v.J};
                });
            },
            py::arg("x"), "S, V, A, J at x (scalar or array, each in [0, 1]) as a dict.")
        .def("__repr__", [](const MotionLaw& law) { return "MotionLaw(" + law.name() + ")"; })
        .def(py::pickle(&law_state, [](const py::tuple& t) { return law_from(t); }));

    py::class_<Segment>(m, "Segment", "One segment of a motion program (angles in rad, lifts in m).")
        .def(py::init([](const MotionLaw& law, double theta_start, double theta_end, double h_start, double h_end) {
                 Segment s{law, theta_start, theta_end, h_start, h_end};
                 s.validate();  // at once, not when a MotionProgram is made of it
                 return s;
             }),
             py::arg("law"), py::arg("theta_start"), py::arg("theta_end"), py::arg("h_start"), py::arg("h_end"))
        .def_readonly("law", &Segment::law)
        .def_readonly("theta_start", &Segment::theta_start)
        .def_readonly("theta_end", &Segment::theta_end)
        .def_readonly("h_start", &Segment::h_start)
        .def_readonly("h_end", &Segment::h_end)
        .def_static(
            "from_table",
            [](const DoubleArray& theta, const DoubleArray& h, int degree, double smoothing,
               const std::vector<double>& start_derivatives, const std::vector<double>& end_derivatives) {
                return Segment::from_table(to_vector(theta, "theta"), to_vector(h, "h"), {degree, smoothing},
                                           start_derivatives, end_derivatives);
            },
            py::arg("theta"), py::arg("h"), py::arg("degree") = 5, py::arg("smoothing") = 0.0,
            py::arg("start_derivatives") = std::vector<double>{}, py::arg("end_derivatives") = std::vector<double>{},
            "A lift table as one segment: a B-spline of odd degree (1, 3, 5 or 7; 5 is C4) through the points\n"
            "(smoothing = 0) or a smoothing spline (smoothing = lambda >= 0, rad^degree: minimizes\n"
            "sum (s(theta_i) - h_i)^2 + lambda * integral (s^(m))^2, m = (degree + 1) / 2). theta absolute\n"
            "(rad, strictly increasing), h in m; the segment spans theta[0]..theta[-1] from h[0] to h[-1].\n"
            "start_derivatives / end_derivatives: h', h'', ... (m/rad^k, up to degree - 1 each) imposed at the\n"
            "ends, as are the end values; empty means zeros up to degree - 1 (joins a dwell C^(degree-1)).")
        .def_static(
            "polynomial", &Segment::polynomial, py::arg("theta_start"), py::arg("theta_end"), py::arg("start"),
            py::arg("end"), py::arg("interior") = std::vector<std::pair<double, double>>{},
            "The polynomial segment meeting start = [h, h', h'', ...] at theta_start and end likewise at theta_end\n"
            "(m, m/rad^k; at least h each) through the interior (theta, h) points (rad strictly inside, m).\n"
            "Degree = number of conditions - 1: ([0, 0, 0], [L, 0, 0]) is the 3-4-5 polynomial. Refuses\n"
            "repeated / outside interior points and ill-conditioned systems (ValueError).")
        .def(
            "lift_at",
            [](const Segment& s, const DoubleArray& theta) {
                return motion_dict(theta, [&](double t) { return s.lift_at(t); });
            },
            py::arg("theta"),
            "The design lift h (m) and dh, d2h, d3h (m/rad^k) at theta in [theta_start, theta_end] (rad), as a dict.")
        .def(py::pickle(
            [](const Segment& s) { return py::make_tuple(s.law, s.theta_start, s.theta_end, s.h_start, s.h_end); },
            [](const py::tuple& t) {
                return Segment{t[0].cast<MotionLaw>(), t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>(),
                               t[4].cast<double>()};
            }))
        .def("__repr__", [](const Segment& s) {
            return detail::concat("Segment(", s.law.name(), ", ", radians_to_degrees(s.theta_start), "-",
                                  radians_to_degrees(s.theta_end), " deg, ", s.h_start, " -> ", s.h_end, " m)");
        });

    py::class_<ProfileError>(
        m, "ProfileError",
        "Manufacturing error of a cam as a lift error e(theta) (m, + = lift higher), as a cam-measuring machine\n"
        "reports it probing with the follower's own roller or face. An immutable sum of components (waviness,\n"
        "dent, Fourier series / fitted table) combined with +; attach it with MotionProgram.with_profile_error.\n"
        "ProfileError() is no error.")
        .def(py::init<>())
        .def_static("waviness", &ProfileError::waviness, py::arg("amplitude"), py::arg("order"), py::arg("phase") = 0.0,
                    "e = amplitude cos(order theta + phase): amplitude in m, order an integer >= 1 (waves per\n"
                    "revolution), phase in rad.")
        .def_static("dent", &ProfileError::dent, py::arg("centre"), py::arg("width"), py::arg("depth"),
                    "Local dent e = -depth (1 - x^2)^4, x = (theta - centre) / (width / 2), zero for |x| >= 1 (C3 at\n"
                    "its edges). centre and width in rad (0 < width <= pi), depth in m (> 0: material missing,\n"
                    "< 0: a bump).")
        .def_static("table", &ProfileError::table, py::arg("theta"), py::arg("error"),
                    py::arg("max_harmonic") = py::none(),
                    "Least-squares Fourier fit of a measured table: theta (rad, >= 3 points, strictly increasing in\n"
                    "[0, 2 pi), any spacing), error (m). max_harmonic in [1, (N - 1) // 2], default the upper end\n"
                    "(interpolation for an odd number of equally spaced points); lower it to smooth a noisy table.")
        .def_static("fourier", &ProfileError::fourier, py::arg("mean"), py::arg("cos"), py::arg("sin"),
                    "e = mean + sum_k cos[k-1] cos(k theta) + sin[k-1] sin(k theta), k = 1..K (m).")
        .def(py::self + py::self)
        .def("__bool__", [](const ProfileError& e) { return !e.empty(); })
        .def("__len__", [](const ProfileError& e) { return e.components().size(); })
        .def_property_readonly(
            "components", [](const ProfileError& e) { return py::list(error_state(e)); },
            "The components as dicts: {'kind': 'waviness' | 'dent' | 'fourier', and its parameters}.")
        .def(
            "evaluate",
            [](const ProfileError& e, const DoubleArray& theta) {
                return map_to_dict<4>(theta, {"e", "de", "d2e", "d3e"}, [&](double t) {
                    const LiftError v = e.evaluate(t);
                    return std::array<double, 4>{v.e, v.de, v.d2e, v.d3e};
                });
            },
            py::arg("theta"),
            "Lift error e (m) and de/dtheta, d2e/dtheta2, d3e/dtheta3 at theta (rad; scalar or array) as a dict.")
        .def("features", &ProfileError::features,
             "Angles (rad, ascending, in [0, 2 pi)) a sampled check must visit: dent centres and edges.")
        .def("__repr__", &error_repr)
        .def(py::pickle(&error_state, &error_from));

    py::class_<BoundaryContinuity>(m, "BoundaryContinuity",
                                   "Continuity at one segment boundary: h, h', h'', h''' (m/rad^k) on each side,\n"
                                   "their jumps (right - left), the tolerances and the order through which the lift\n"
                                   "is continuous (-1: h jumps, ..., 3: C3 at least).")
        .def_readonly("left_segment", &BoundaryContinuity::left_segment, "Index of the segment ending here.")
        .def_readonly("right_segment", &BoundaryContinuity::right_segment,
                      "Index of the segment starting here (0 at the wrap).")
        .def_readonly("theta", &BoundaryContinuity::theta, "Angle of the boundary (rad; the wrap at 0).")
        .def_readonly("left", &BoundaryContinuity::left, "h, h', h'', h''' as the left segment ends.")
        .def_readonly("right", &BoundaryContinuity::right, "h, h', h'', h''' as the right segment starts.")
        .def_readonly("jump", &BoundaryContinuity::jump, "right - left for h, h', h'', h''' (m/rad^k).")
        .def_readonly("tolerance", &BoundaryContinuity::tolerance,
                      "Jumps up to these count as none (1e-6 of each derivative's scale).")
        .def_readonly("continuous_through", &BoundaryContinuity::continuous_through,
                      "Highest k with h..h^(k) continuous: -1, 0, 1, 2 or 3 (3: C3 at least).")
        .def("__repr__", [](const BoundaryContinuity& b) {
            return detail::concat("BoundaryContinuity(segments ", b.left_segment, " -> ", b.right_segment, " at ",
                                  radians_to_degrees(b.theta), " deg, continuous through order ", b.continuous_through,
                                  ")");
        });

    py::class_<ContinuityReport>(m, "ContinuityReport",
                                 "Continuity of a program at each segment boundary (the wrap at 360 deg last).")
        .def_readonly("boundaries", &ContinuityReport::boundaries, "One BoundaryContinuity per segment end.")
        .def_property_readonly("continuous_through", &ContinuityReport::continuous_through,
                               "The program's order of continuity: the lowest over its boundaries.")
        .def("__len__", [](const ContinuityReport& r) { return r.boundaries.size(); })
        .def("__getitem__",
             [](const ContinuityReport& r, py::ssize_t i) {
                 const py::ssize_t n = static_cast<py::ssize_t>(r.boundaries.size());
                 if (i < 0) i += n;
                 if (i < 0 || i >= n) throw py::index_error("boundary index out of range");
                 return r.boundaries[static_cast<std::size_t>(i)];
             })
        .def("__repr__", [](const ContinuityReport& r) {
            return detail::concat("ContinuityReport(", r.boundaries.size(), " boundaries, continuous through order ",
                                  r.continuous_through(), ")");
        });

    py::class_<MotionProgram>(m, "MotionProgram", "Segments tiling one revolution; h(theta) and its theta-derivatives.")
        .def(py::init<std::vector<Segment>>(), py::arg("segments"))
        .def_static("paper_default", &MotionProgram::paper_default, py::arg("total_rise") = 0.010,
                    "Paper Table 1: dwell 0-30, modified-trapezoid rise 30-180, dwell 180-210, return 210-360 deg.")
        .def_static(
            "from_table",
            [](const DoubleArray& theta, const DoubleArray& h, int degree, double smoothing) {
                return MotionProgram::from_table(to_vector(theta, "theta"), to_vector(h, "h"), {degree, smoothing});
            },
            py::arg("theta"), py::arg("h"), py::arg("degree") = 5, py::arg("smoothing") = 0.0,
            "A whole revolution from a lift table, as one periodic B-spline segment. theta strictly increasing in\n"
            "[0, 2 pi) (rad), h in m. The table is NOT closed: the spline joins the last point to the first one\n"
            "revolution later (a repeated first point at theta[0] + 2 pi with the same h is dropped; with another\n"
            "h, refused). degree odd (1, 3, 5, 7; 5: C4); smoothing = lambda >= 0 (rad^degree): the fit minimizes\n"
            "sum (s(theta_i) - h_i)^2 + lambda * integral (s^(m))^2, m = (degree + 1) / 2; for N equally spaced\n"
            "points, harmonic k keeps 1 / (1 + lambda (2 pi / N) k^(2m)) of its amplitude.")
        .def_property_readonly("segments", &MotionProgram::segments)
        .def("continuity", &MotionProgram::continuity,
             "Jumps of h, h', h'', h''' at every segment boundary (the wrap included) and the order through which\n"
             "the design lift is continuous there (a ContinuityReport).")
        .def("require_continuity", &MotionProgram::require_continuity, py::arg("order"),
             "Raise ValueError naming the first boundary (segments, angle in deg) where h .. h^(order) jumps;\n"
             "order 0 (lift), 1 (velocity), 2 (acceleration) or 3 (jerk).")
        .def(
            "smoothness",
            [](const MotionProgram& p, std::size_t excursions) { return smoothness_dict(smoothness(p, excursions)); },
            py::arg("excursions") = 5,
            "Per-radian smoothness report as a dict: peaks {'velocity', 'acceleration', 'jerk'}: {'value' (m/rad^k),\n"
            "'theta' (rad)}; 'table_points'; 'residual' {'max', 'rms' (m), 'theta_of_max'} of the spline tables;\n"
            "'jerk_roughness' (RMS local jerk excursion / peak jerk: < 0.01 smooth, 0.1-0.5 noisy) and\n"
            "'jerk_excursions': the largest local excursions [{'theta', 'excursion' (m/rad^3)}], largest first.\n"
            "camfollower.motion.smoothness adds physical units at a speed.")
        .def(py::pickle(
            [](const MotionProgram& p) {
                const ProfileError* e = p.profile_error();
                return py::make_tuple(p.segments(), e ? py::cast(*e) : py::none());
            },
            [](const py::tuple& t) {  // (segments,) from before profile errors, or (segments, error | None)
                MotionProgram p(t[0].cast<std::vector<Segment>>());
                if (t.size() > 1 && !t[1].is_none()) p = p.with_profile_error(t[1].cast<ProfileError>());
                return p;
            }))
        .def("complement", &MotionProgram::complement, py::arg("total"),
             "The conjugate program total - h(theta) (a conjugate pair's return cam), from the design lift (a\n"
             "profile error is not carried over); built-in laws only: a spline or polynomial segment is refused.")
        .def("with_profile_error", &MotionProgram::with_profile_error, py::arg("error"),
             "A copy whose lift carries the cam's manufacturing error (replacing any it carries; ProfileError()\n"
             "removes it). It reaches evaluate, the contacts and the undercut / pressure-angle checks.")
        .def_property_readonly(
            "profile_error",
            [](const MotionProgram& p) -> std::optional<ProfileError> {
                if (const ProfileError* e = p.profile_error()) return *e;
                return std::nullopt;
            },
            "The manufacturing error the lift carries, None for the design program.")
        .def("max_lift", &MotionProgram::max_lift, "Largest lift over the revolution, profile error included (m).")
        .def("min_lift", &MotionProgram::min_lift, "Smallest lift over the revolution, profile error included (m).")
        .def(
            "evaluate",
            [](const MotionProgram& p, const DoubleArray& theta) {
                return map_to_dict<4>(theta, {"h", "dh", "d2h", "d3h"}, [&](double t) {
                    const FollowerMotion v = p.evaluate(t);
                    return std::array<double, 4>{v.h, v.dh, v.d2h, v.d3h};
                });
            },
            py::arg("theta"),
            "Lift h (m) and dh/dtheta, d2h/dtheta2, d3h/dtheta3 at theta (rad; scalar or array) as a dict.");
}

}  // namespace camfollower::python
