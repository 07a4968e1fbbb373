// Bindings for include/camfollower/motion: laws, profile errors and programs.
#include <optional>

#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/motion/profile_error.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower::python {

namespace {
MotionLaw law_from(const py::tuple& t) {
    switch (LawKind(t[0].cast<int>())) {
        case LawKind::dwell: return MotionLaw::dwell();
        case LawKind::simple_harmonic: return MotionLaw::simple_harmonic();
        case LawKind::cycloidal: return MotionLaw::cycloidal();
        case LawKind::polynomial_345: return MotionLaw::polynomial_345();
        case LawKind::polynomial_4567: return MotionLaw::polynomial_4567();
        case LawKind::constant_acceleration: return MotionLaw::constant_acceleration();
        case LawKind::sine_constant_cosine:
            return MotionLaw::sine_constant_cosine(t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>());
    }
    detail::fail("MotionLaw: invalid pickled state");
}

// One component as a dict: {"kind": "waviness" | "dent" | "fourier", its parameters}. Also the
// pickled form, rebuilt through the validating constructors.
py::dict component_dict(const ProfileError::Component& c) {
    if (const auto* w = std::get_if<ProfileError::Waviness>(&c))
        return py::dict(py::arg("kind") = "waviness", py::arg("amplitude") = w->amplitude,
                        py::arg("order") = w->order, py::arg("phase") = w->phase);
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
        else
            out += detail::concat("fourier(", std::get<ProfileError::Fourier>(c).cos.size(), " harmonics)");
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

    py::class_<MotionLaw>(m, "MotionLaw",
                          "Normalized motion law S(x) on x in [0, 1], S(0) = 0, S(1) = 1. Build one with a "
                          "static method (MotionLaw.modified_trapezoid(), ...).")
        .def_static("dwell", &MotionLaw::dwell)
        .def_static("simple_harmonic", &MotionLaw::simple_harmonic)
        .def_static("cycloidal", &MotionLaw::cycloidal)
        .def_static("modified_trapezoid", &MotionLaw::modified_trapezoid)
        .def_static("modified_sine", &MotionLaw::modified_sine)
        .def_static("polynomial_345", &MotionLaw::polynomial_345)
        .def_static("polynomial_4567", &MotionLaw::polynomial_4567)
        .def_static("constant_acceleration", &MotionLaw::constant_acceleration)
        .def_static("sine_constant_cosine", &MotionLaw::sine_constant_cosine, py::arg("b"), py::arg("c"),
                    py::arg("d"),
                    "Sine-constant-cosine acceleration family; b + c + d = 1 (fractions of the segment).")
        .def_property_readonly("name", &MotionLaw::name)
        .def_property_readonly("b", &MotionLaw::b)
        .def_property_readonly("c", &MotionLaw::c)
        .def_property_readonly("d", &MotionLaw::d)
        .def("peaks", &MotionLaw::peaks, "Peak coefficients C_v, C_a, C_j.")
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
        .def(py::pickle([](const MotionLaw& law) { return py::make_tuple(int(law.kind()), law.b(), law.c(), law.d()); },
                        [](const py::tuple& t) { return law_from(t); }));

    py::class_<Segment>(m, "Segment", "One segment of a motion program (angles in rad, lifts in m).")
        .def(py::init([](const MotionLaw& law, double theta_start, double theta_end, double h_start,
                         double h_end) { return Segment{law, theta_start, theta_end, h_start, h_end}; }),
             py::arg("law"), py::arg("theta_start"), py::arg("theta_end"), py::arg("h_start"), py::arg("h_end"))
        .def_readonly("law", &Segment::law)
        .def_readonly("theta_start", &Segment::theta_start)
        .def_readonly("theta_end", &Segment::theta_end)
        .def_readonly("h_start", &Segment::h_start)
        .def_readonly("h_end", &Segment::h_end)
        .def(py::pickle([](const Segment& s) { return py::make_tuple(s.law, s.theta_start, s.theta_end, s.h_start, s.h_end); },
                        [](const py::tuple& t) {
                            return Segment{t[0].cast<MotionLaw>(), t[1].cast<double>(), t[2].cast<double>(),
                                           t[3].cast<double>(), t[4].cast<double>()};
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
        .def_static("table", &ProfileError::table, py::arg("theta"), py::arg("error"), py::arg("max_harmonic") = py::none(),
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

    py::class_<MotionProgram>(m, "MotionProgram",
                              "Segments tiling one revolution; h(theta) and its theta-derivatives.")
        .def(py::init<std::vector<Segment>>(), py::arg("segments"))
        .def_static("paper_default", &MotionProgram::paper_default, py::arg("total_rise") = 0.010,
                    "Paper Table 1: dwell 0-30, modified-trapezoid rise 30-180, dwell 180-210, return 210-360 deg.")
        .def_property_readonly("segments", &MotionProgram::segments)
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
