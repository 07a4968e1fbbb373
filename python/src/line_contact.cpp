// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/contact/line_contact.hpp: Hertz contact stress of the roller (or
// flat face) on the cam, and Palmgren's roller law.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "camfollower/contact/line_contact.hpp"

namespace camfollower::python {

namespace {

const double inf = std::numeric_limits<double>::infinity();

// A crowned roller whose radius ratio leaves the Hamrock-Brewe fits' range: a UserWarning (once per
// call), not an error: the numbers are still Hertz to within several per cent.
std::string g4(double x) {  // 4 significant digits: a message, not a result
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", x);
    return text;
}

void warn_beyond_fits(const LineContact& c, double ratio, double rolling_radius, py::ssize_t count = 1) {
    if (!(ratio > hamrock_brewe_max_ratio)) return;
    const std::string where = count > 1 ? detail::concat(" at ", count, " angles, up to") : std::string();
    const std::string message = detail::concat(
        "crowned roller: the radius ratio", where, " ", g4(ratio), " (crown_radius ", g4(c.crown_radius),
        " m against the relative radius ", g4(rolling_radius), " m along the rolling direction) is beyond the ",
        "Hamrock-Brewe fits' range 1 to ", hamrock_brewe_max_ratio, ", where they are within 5.4 % of exact Hertz; ",
        "beyond it the semi-axis a is off by +5.7 % at 150, +6.9 % at 200, +15 % at 1000 (docs/contact_stress.md)");
    if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) < 0) throw py::error_already_set();
}

py::dict stress_dict(const LineContact& c, const ContactStress& s) {
    py::dict d;
    d["half_width"] = s.half_width;
    d["max_pressure"] = s.max_pressure;
    d["effective_radius"] = s.effective_radius;
    if (c.crowned()) {
        d["a"] = s.semi_axis;
        d["b"] = s.half_width;
        d["approach"] = s.approach;
        d["radius_ratio"] = s.radius_ratio;
        warn_beyond_fits(c, s.radius_ratio, s.effective_radius);
    }
    return d;
}

// Stress over theta for one follower type; force is one value or one per angle (same shape).
template <class Follower>
py::dict profile_stress_dict(const LineContact& c, const Follower& follower, const MotionProgram& program,
                             const DoubleArray& force, const DoubleArray& theta) {
    const py::ssize_t n = theta.size();
    if (force.size() != 1 && force.size() != n)
        detail::fail("force must be a scalar or have one value per angle (", n, "), got ", force.size());
    std::vector<py::ssize_t> shape(theta.shape(), theta.shape() + theta.ndim());
    const char* names[4] = {"half_width", "max_pressure", "effective_radius", "surface_radius"};
    py::array_t<double> out[4];
    double* dst[4];
    for (int k = 0; k < 4; ++k) out[k] = py::array_t<double>(shape), dst[k] = out[k].mutable_data();
    const double* t = theta.data();
    const double* f = force.data();
    double worst_ratio = 0.0, worst_radius = 0.0;
    py::ssize_t beyond = 0;
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const ContactStress s = profile_stress(c, program, follower, t[i], f[force.size() == 1 ? 0 : i]);
            dst[0][i] = s.half_width, dst[1][i] = s.max_pressure, dst[2][i] = s.effective_radius;
            dst[3][i] = follower.profile(t[i], program.evaluate(t[i])).surface_radius;
            if (s.radius_ratio > hamrock_brewe_max_ratio) ++beyond;
            if (s.radius_ratio > worst_ratio) worst_ratio = s.radius_ratio, worst_radius = s.effective_radius;
        }
    }
    warn_beyond_fits(c, worst_ratio, worst_radius, beyond);
    py::dict d;
    for (int k = 0; k < 4; ++k) {
        if (theta.ndim() == 0) d[names[k]] = py::float_(dst[k][0]);
        else d[names[k]] = out[k];
    }
    return d;
}

}  // namespace

void bind_line_contact(py::module_& m) {
    py::class_<Elastic>(m, "Elastic", "Elastic constants of one body: Young's modulus (Pa) and Poisson's ratio.")
        .def(py::init([](double E, double nu) {
                 Elastic e{E, nu};
                 e.validate();
                 return e;
             }),
             py::arg("youngs_modulus") = 210e9, py::arg("poisson_ratio") = 0.3)
        .def_static("steel", &Elastic::steel, "E = 210 GPa, nu = 0.3.")
        .def_readonly("youngs_modulus", &Elastic::youngs_modulus, "Young's modulus E (Pa)")
        .def_readonly("poisson_ratio", &Elastic::poisson_ratio, "Poisson's ratio nu, [0, 0.5)")
        .def_static("effective_modulus", &effective_modulus, py::arg("a"), py::arg("b"),
                    "Contact modulus E* (Pa): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.")
        .def("__repr__", [](const Elastic& e) {
            return detail::concat("Elastic(youngs_modulus=", e.youngs_modulus, ", poisson_ratio=", e.poisson_ratio,
                                  ")");
        });

    py::class_<LineContact>(m, "LineContact",
                            "Hertz contact of a roller of width `length` (m) on the cam: straight (line contact, "
                            "Johnson ch. 4) or crowned with crown_radius (m; elliptical contact, Hamrock-Brewe fits, "
                            "made for radius ratios 1 to 100).")
        .def(py::init([](double length, const Elastic& roller, const Elastic& cam, double crown_radius) {
                 LineContact c{length, roller, cam, crown_radius};
                 c.validate();
                 return c;
             }),
             py::arg("length"), py::arg("roller") = Elastic::steel(), py::arg("cam") = Elastic::steel(),
             py::arg("crown_radius") = inf)
        .def_readonly("length", &LineContact::length, "roller width L (m)")
        .def_readonly("roller", &LineContact::roller)
        .def_readonly("cam", &LineContact::cam)
        .def_readonly("crown_radius", &LineContact::crown_radius, "crown radius (m); inf: straight roller")
        .def_property_readonly("crowned", &LineContact::crowned)
        .def_property_readonly(
            "effective_modulus", [](const LineContact& c) { return effective_modulus(c.roller, c.cam); },
            "contact modulus E* (Pa)")
        .def(
            "stress",
            [](const LineContact& c, double force, double radius, double cam_radius) {
                return stress_dict(c, c.stress(force, radius, cam_radius));
            },
            py::arg("force"), py::arg("radius"), py::arg("cam_radius") = inf,
            "Contact stress for a normal force (N) between the roller of radius `radius` and a cam of\n"
            "radius cam_radius (m; > 0 convex, < 0 concave, inf flat). Keys: half_width (m, along the\n"
            "rolling direction), max_pressure (Pa), effective_radius (m); crowned also a (semi-axis\n"
            "across the width), b (= half_width), approach (m) and radius_ratio (crown radius over the\n"
            "rolling radius, or its inverse: >= 1). The crowned values come from Hamrock-Brewe fits made\n"
            "for radius ratios 1 to 100, within 5.4 % of exact Hertz there; beyond 100 (a long crown on a\n"
            "small roller) they drift (a +6.9 % at 200, +15 % at 1000) and a UserWarning says so.")
        .def(
            "profile_stress",
            [](const LineContact& c, const py::object& follower, const MotionProgram& program, const DoubleArray& force,
               const DoubleArray& theta) {
                return std::visit([&](const auto& f) { return profile_stress_dict(c, f, program, force, theta); },
                                  follower_from(follower));
            },
            py::arg("follower"), py::arg("program"), py::arg("force"), py::arg("theta"),
            "Contact stress along the cam at theta (rad, scalar or array) for force (N, scalar or one per\n"
            "angle). The roller radius is the follower's (a flat face is a plane). Keys: half_width (m),\n"
            "max_pressure (Pa), effective_radius (m), surface_radius (m, the cam's, signed). A crowned\n"
            "roller whose radius ratio leaves the fits' range 1 to 100 at some angles: one UserWarning.")
        .def_static(
            "palmgren_law",
            [](double length, double damping_factor) {
                const HertzContact law = palmgren_law(length, damping_factor);
                py::dict d;
                d["stiffness"] = law.stiffness;
                d["exponent"] = law.exponent;
                d["damping_factor"] = law.damping_factor;
                return d;
            },
            py::arg("length"), py::arg("damping_factor") = 0.0,
            "Palmgren's steel roller law F = K delta^(10/9) for roller width `length` (m): dict with\n"
            "stiffness (N/m^(10/9)), exponent (10/9), damping_factor (s/m), the keys of a contact law.")
        .def("__repr__", [](const LineContact& c) {
            return detail::concat("LineContact(length=", c.length, ", roller=Elastic(", c.roller.youngs_modulus, ", ",
                                  c.roller.poisson_ratio, "), cam=Elastic(", c.cam.youngs_modulus, ", ",
                                  c.cam.poisson_ratio, "), crown_radius=", c.crown_radius, ")");
        });
}

}  // namespace camfollower::python
