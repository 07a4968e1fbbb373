// SPDX-License-Identifier: BSD-3-Clause
// The camshaft's speed program (motion/speed_program.hpp): ramps, a modulation, the angle, speed and
// acceleration at any time.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/motion/speed_program.hpp"

namespace camfollower::python {

namespace {
py::tuple ramp_state(const SpeedRamp& r) {
    return py::make_tuple(r.start, r.duration, r.to_speed, ramp_shape_name(r.shape));
}
std::string num(double x) { return std::string(py::repr(py::float_(x))); }  // reads back exactly
SpeedRamp ramp_from(const py::tuple& t) {
    return {t[0].cast<double>(), t[1].cast<double>(), t[2].cast<double>(), ramp_shape_from(t[3].cast<std::string>())};
}
}  // namespace

void bind_speed(py::module_& m) {
    py::class_<SpeedRamp>(m, "SpeedRamp",
                          "A change of the camshaft's base speed to to_speed (rad/s, >= 0) over [start, start +\n"
                          "duration] (s). shape 'smooth' (the acceleration rises and falls as 1 - cos: no step in it)\n"
                          "or 'linear' (a constant acceleration, stepping at the ends).")
        .def(py::init([](double start, double duration, double to_speed, const std::string& shape) {
                 return SpeedRamp{start, duration, to_speed, ramp_shape_from(shape)};
             }),
             py::arg("start"), py::arg("duration"), py::arg("to_speed"), py::arg("shape") = "smooth")
        .def_readonly("start", &SpeedRamp::start, "s")
        .def_readonly("duration", &SpeedRamp::duration, "s")
        .def_readonly("to_speed", &SpeedRamp::to_speed, "rad/s")
        .def_property_readonly(
            "shape", [](const SpeedRamp& r) { return std::string(ramp_shape_name(r.shape)); }, "'smooth' or 'linear'")
        .def(py::pickle(&ramp_state, &ramp_from))
        .def("__repr__", [](const SpeedRamp& r) {
            return "SpeedRamp(start=" + num(r.start) + ", duration=" + num(r.duration) +
                   ", to_speed=" + num(r.to_speed) + ", shape='" + ramp_shape_name(r.shape) + "')";
        });

    py::class_<SpeedModulation>(m, "SpeedModulation",
                                "speed = base speed * (1 + amplitude sin(harmonic theta_base + phase)): amplitude in\n"
                                "(-1, 1), harmonic a whole number of speed cycles per revolution, phase in rad.")
        .def(py::init([](double amplitude, int harmonic, double phase) {
                 return SpeedModulation{amplitude, harmonic, phase};
             }),
             py::arg("amplitude"), py::arg("harmonic") = 1, py::arg("phase") = 0.0)
        .def_readonly("amplitude", &SpeedModulation::amplitude)
        .def_readonly("harmonic", &SpeedModulation::harmonic)
        .def_readonly("phase", &SpeedModulation::phase, "rad")
        .def(py::pickle([](const SpeedModulation& s) { return py::make_tuple(s.amplitude, s.harmonic, s.phase); },
                        [](const py::tuple& t) {
                            return SpeedModulation{t[0].cast<double>(), t[1].cast<int>(), t[2].cast<double>()};
                        }))
        .def("__repr__", [](const SpeedModulation& s) {
            return "SpeedModulation(amplitude=" + num(s.amplitude) + ", harmonic=" + std::to_string(s.harmonic) +
                   ", phase=" + num(s.phase) + ")";
        });

    py::class_<SpeedProgram>(
        m, "SpeedProgram",
        "The camshaft's rotation over time: initial_speed (rad/s, >= 0), then the ramps in time order from t >= 0,\n"
        "and an optional modulation on top; angle 0 at t = 0. Closed-form angle, speed and acceleration.\n"
        "Give it to MechanismBuilder.speed_program: camshaft_speed becomes its nominal (highest base) speed,\n"
        "and changing that speed scales the whole program.")
        .def(py::init<double, std::vector<SpeedRamp>, std::optional<SpeedModulation>>(), py::arg("initial_speed"),
             py::arg("ramps") = std::vector<SpeedRamp>{}, py::arg("modulation") = std::nullopt)
        .def_static("constant", &SpeedProgram::constant, py::arg("speed"), "Turning at `speed` rad/s.")
        .def_property_readonly("initial_speed", &SpeedProgram::initial_speed, "rad/s")
        .def_property_readonly("ramps", &SpeedProgram::ramps)
        .def_property_readonly("modulation", &SpeedProgram::modulation)
        .def_property_readonly("nominal_speed", &SpeedProgram::nominal_speed, "the highest base speed, rad/s")
        .def_property_readonly("constant_speed", &SpeedProgram::is_constant, "turning at one speed all the time")
        .def_property_readonly("periodic", &SpeedProgram::periodic,
                               "the motion repeats every revolution (no ramps): a periodic steady state exists")
        .def("scaled_to", &SpeedProgram::scaled_to, py::arg("speed"),
             "The same program with its base speeds scaled to the nominal speed `speed` (rad/s).")
        .def(
            "evaluate",
            [](const SpeedProgram& p, const DoubleArray& t) {
                return map_to_dict<3>(t, {"angle", "speed", "acceleration"}, [&](double x) {
                    detail::require_finite(x, "t");
                    const DriveState d = p.at(x);
                    return std::array<double, 3>{d.angle, d.rate, d.acceleration};
                });
            },
            py::arg("t"),
            "The camshaft's angle (rad), speed (rad/s) and angular acceleration (rad/s^2) at t (s; scalar or\n"
            "array) as a dict.")
        .def("time_at_angle", &SpeedProgram::time_at_angle, py::arg("angle"),
             "The first time (s) the camshaft reaches `angle` (rad).")
        .def(py::pickle(
            [](const SpeedProgram& p) { return py::make_tuple(p.initial_speed(), p.ramps(), p.modulation()); },
            [](const py::tuple& t) {
                return SpeedProgram(t[0].cast<double>(), t[1].cast<std::vector<SpeedRamp>>(),
                                    t[2].cast<std::optional<SpeedModulation>>());
            }))
        .def("__repr__", [](const SpeedProgram& p) {
            return "SpeedProgram(initial_speed=" + num(p.initial_speed()) +
                   ", ramps=" + std::string(py::repr(py::cast(p.ramps()))) +
                   ", modulation=" + std::string(py::repr(py::cast(p.modulation()))) + ")";
        });
}

}  // namespace camfollower::python
