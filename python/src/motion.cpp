// Bindings for include/camfollower/motion: laws and programs.
#include <pybind11/stl.h>

#include "bindings.hpp"
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

    py::class_<MotionProgram>(m, "MotionProgram",
                              "Segments tiling one revolution; h(theta) and its theta-derivatives.")
        .def(py::init<std::vector<Segment>>(), py::arg("segments"))
        .def_static("paper_default", &MotionProgram::paper_default, py::arg("total_rise") = 0.010,
                    "Paper Table 1: dwell 0-30, modified-trapezoid rise 30-180, dwell 180-210, return 210-360 deg.")
        .def_property_readonly("segments", &MotionProgram::segments)
        .def(py::pickle([](const MotionProgram& p) { return py::make_tuple(p.segments()); },
                        [](const py::tuple& t) { return MotionProgram(t[0].cast<std::vector<Segment>>()); }))
        .def("max_lift", &MotionProgram::max_lift)
        .def("min_lift", &MotionProgram::min_lift)
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
