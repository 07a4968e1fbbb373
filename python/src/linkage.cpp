// SPDX-License-Identifier: BSD-3-Clause
// Cam-driven linkages (linkage/coupler_linkage.hpp): the swing arm - coupler - slider and the four-bar,
// their rigid output and its SVAJ, the backward solution, and MechanismBuilder.add_linkage.
#include <cmath>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/linkage/coupler_linkage.hpp"
#include "camfollower/model/mechanism_builder.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower::python {

namespace {
const char* output_name(CouplerLinkage::Output o) { return o == CouplerLinkage::Output::slider ? "slider" : "rocker"; }
CouplerLinkage::Output output_from(const std::string& s) {
    if (s == "slider") return CouplerLinkage::Output::slider;
    if (s == "rocker") return CouplerLinkage::Output::rocker;
    detail::fail("linkage output must be 'slider' or 'rocker', got '", s, "'");
}
}  // namespace

void bind_linkage(py::module_& m) {
    py::class_<CouplerLinkage>(
        m, "CouplerLinkage",
        "A cam-driven linkage in its own plane frame (m, rad): the swing arm (arm_dof, the follower's DOF) turning\n"
        "about arm_pivot, its pin at arm_length and at arm_angle when q = 0, lifting in the sense arm_turn; a\n"
        "coupler of coupler_length (m), coupler_mass (kg) and coupler_inertia about its mid-length (kg m^2); the\n"
        "output a 'slider' (output_dof in m along the line through output_origin at output_direction) or a\n"
        "'rocker' (output_dof in rad about the pivot output_origin, pin at output_length, positive in\n"
        "output_turn); branch +1/-1 picks the assembly. In a mechanism (MechanismBuilder.add_linkage) the coupler\n"
        "is a rigid body with DOFs <name>.x, <name>.y, <name>.angle joined to the two pins by pin joints\n"
        "<name>.input, <name>.output of joint_stiffness (N/m) and joint_damping (N s/m).")
        .def(py::init([](const std::string& name, const std::string& arm_dof, const std::string& output_dof,
                         const Eigen::Vector2d& arm_pivot, double arm_length, double arm_angle,
                         const py::object& arm_turn, double coupler_length, double coupler_mass, double coupler_inertia,
                         const std::string& output, const Eigen::Vector2d& output_origin, double output_direction,
                         double output_length, const py::object& output_turn, int branch, double joint_stiffness,
                         double joint_damping) {
                 CouplerLinkage l;
                 l.name = name, l.arm_dof = arm_dof, l.output_dof = output_dof;
                 l.arm_pivot = arm_pivot, l.arm_length = arm_length, l.arm_angle = arm_angle;
                 l.arm_turn = turn_argument(arm_turn);
                 l.coupler_length = coupler_length, l.coupler_mass = coupler_mass;
                 l.coupler_inertia = coupler_inertia;
                 l.output = output_from(output), l.output_origin = output_origin;
                 l.output_direction = output_direction, l.output_length = output_length;
                 l.output_turn = turn_argument(output_turn);
                 l.branch = branch, l.joint_stiffness = joint_stiffness, l.joint_damping = joint_damping;
                 l.validate();
                 return l;
             }),
             py::arg("name"), py::arg("arm_dof"), py::arg("output_dof"), py::kw_only(),
             py::arg("arm_pivot") = Eigen::Vector2d::Zero().eval(), py::arg("arm_length"), py::arg("arm_angle"),
             py::arg("arm_turn") = "counter_clockwise", py::arg("coupler_length"), py::arg("coupler_mass"),
             py::arg("coupler_inertia"), py::arg("output") = "slider",
             py::arg("output_origin") = Eigen::Vector2d::Zero().eval(), py::arg("output_direction") = 0.0,
             py::arg("output_length") = 0.0, py::arg("output_turn") = "counter_clockwise", py::arg("branch") = 1,
             py::arg("joint_stiffness"), py::arg("joint_damping") = 0.0)
        .def_readonly("name", &CouplerLinkage::name)
        .def_readonly("arm_dof", &CouplerLinkage::arm_dof)
        .def_readonly("output_dof", &CouplerLinkage::output_dof)
        .def_readonly("arm_length", &CouplerLinkage::arm_length, "m")
        .def_readonly("arm_angle", &CouplerLinkage::arm_angle, "rad")
        .def_readonly("coupler_length", &CouplerLinkage::coupler_length, "m")
        .def_readonly("coupler_mass", &CouplerLinkage::coupler_mass, "kg")
        .def_readonly("coupler_inertia", &CouplerLinkage::coupler_inertia, "kg m^2")
        .def_property_readonly("output", [](const CouplerLinkage& l) { return std::string(output_name(l.output)); })
        .def_readonly("branch", &CouplerLinkage::branch)
        .def_readonly("joint_stiffness", &CouplerLinkage::joint_stiffness, "N/m")
        .def_readonly("joint_damping", &CouplerLinkage::joint_damping, "N s/m")
        .def(
            "output_at",
            [](const CouplerLinkage& l, const DoubleArray& q) {
                const py::dict d =
                    map_to_dict<1>(q, {"s"}, [&](double x) { return std::array<double, 1>{l.output_at(x)}; });
                return py::object(d["s"]);
            },
            py::arg("q"),
            "The rigid linkage's output displacement (m or rad from its reference) at the arm's displacement q (rad;\n"
            "scalar or array). Raises ValueError where the linkage cannot close.")
        .def(
            "input_at",
            [](const CouplerLinkage& l, const DoubleArray& s) {
                const py::dict d =
                    map_to_dict<1>(s, {"q"}, [&](double x) { return std::array<double, 1>{l.input_at(x)}; });
                return py::object(d["q"]);
            },
            py::arg("s"), "The arm's displacement (rad) that puts the output at s (the inverse of output_at).")
        .def(
            "svaj",
            [](const CouplerLinkage& l, const MotionProgram& program, const DoubleArray& theta) {
                return map_to_dict<4>(theta, {"s", "ds", "d2s", "d3s"}, [&](double t) {
                    const FollowerMotion h = program.evaluate(t);
                    const Taylor3 s = l.output_displacement(Taylor3(h.h, h.dh, h.d2h, h.d3h));
                    return std::array<double, 4>{s.v, s.d1, s.d2, s.d3};
                });
            },
            py::arg("program"), py::arg("theta"),
            "The output's displacement and its derivatives per radian of cam angle (s, ds, d2s, d3s) when the arm\n"
            "follows `program` (its lift, rad): exact (Taylor arithmetic through the closed-form linkage). Times\n"
            "omega^k for velocity, acceleration and jerk at a constant speed.")
        .def(
            "backward",
            [](const CouplerLinkage& l, const MotionProgram& wanted, int points, int degree) {
                if (points < 8 || points > 1000000)
                    detail::fail("backward: points must be in [8, 1000000], got ", points);
                std::vector<double> theta(static_cast<std::size_t>(points)), q(theta.size());
                for (int i = 0; i < points; ++i) {
                    theta[std::size_t(i)] = two_pi * i / points;
                    q[std::size_t(i)] = l.input_at(wanted.evaluate(theta[std::size_t(i)]).h);
                }
                return MotionProgram::from_table(theta, q, {degree, 0.0});
            },
            py::arg("wanted"), py::arg("points") = 3600, py::arg("degree") = 5,
            "The backward solution: the arm's lift program (rad) that moves the output by `wanted` (its displacement\n"
            "from the reference, m or rad, per cam angle), from the inverse linkage at `points` equally spaced cam\n"
            "angles, fitted by a periodic B-spline of `degree` (MotionProgram.from_table).")
        .def(py::pickle(
            [](const CouplerLinkage& l) {
                return py::make_tuple(l.name, l.arm_dof, l.output_dof, l.arm_pivot, l.arm_length, l.arm_angle,
                                      arm_turn_name(l.arm_turn), l.coupler_length, l.coupler_mass, l.coupler_inertia,
                                      output_name(l.output), l.output_origin, l.output_direction, l.output_length,
                                      arm_turn_name(l.output_turn), l.branch, l.joint_stiffness, l.joint_damping);
            },
            [](const py::tuple& t) {
                CouplerLinkage l;
                l.name = t[0].cast<std::string>(), l.arm_dof = t[1].cast<std::string>();
                l.output_dof = t[2].cast<std::string>(), l.arm_pivot = t[3].cast<Eigen::Vector2d>();
                l.arm_length = t[4].cast<double>(), l.arm_angle = t[5].cast<double>();
                l.arm_turn = arm_turn_from(t[6].cast<std::string>()), l.coupler_length = t[7].cast<double>();
                l.coupler_mass = t[8].cast<double>(), l.coupler_inertia = t[9].cast<double>();
                l.output = output_from(t[10].cast<std::string>()), l.output_origin = t[11].cast<Eigen::Vector2d>();
                l.output_direction = t[12].cast<double>(), l.output_length = t[13].cast<double>();
                l.output_turn = arm_turn_from(t[14].cast<std::string>()), l.branch = t[15].cast<int>();
                l.joint_stiffness = t[16].cast<double>(), l.joint_damping = t[17].cast<double>();
                l.validate();
                return l;
            }))
        .def("__repr__", [](const CouplerLinkage& l) {
            return detail::concat("CouplerLinkage('", l.name, "', '", l.arm_dof, "' -> ", output_name(l.output), " '",
                                  l.output_dof, "')");
        });
}

}  // namespace camfollower::python
