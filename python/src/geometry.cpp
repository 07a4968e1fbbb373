// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/geometry: the disk cam with offset translating roller follower.
#include <optional>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/geometry/disk_cam.hpp"

namespace camfollower::python {

void bind_geometry(py::module_& m) {
    py::class_<DiskCam>(m, "DiskCam",
                        "Disk cam with an offset translating roller follower (lengths in m, angles in rad).")
        .def(py::init([](const std::optional<MotionProgram>& program, double base_radius, double roller_radius,
                         double offset) {
                 return DiskCam(DiskCamGeometry{base_radius, roller_radius, offset},
                                program ? *program : MotionProgram::paper_default());
             }),
             py::arg("program") = py::none(), py::arg("base_radius") = 0.030, py::arg("roller_radius") = 0.008,
             py::arg("offset") = 0.010)
        .def_property_readonly("program", &DiskCam::program)
        .def_property_readonly("base_radius", [](const DiskCam& c) { return c.geometry().base_radius; })
        .def_property_readonly("roller_radius", [](const DiskCam& c) { return c.geometry().roller_radius; })
        .def_property_readonly("offset", [](const DiskCam& c) { return c.geometry().offset; })
        .def(
            "profile",
            [](const DiskCam& cam, const DoubleArray& theta, std::optional<double> offset) {
                const double e = offset.value_or(cam.geometry().offset);
                cam.check_offset(e, "offset");
                return map_to_dict<14>(
                    theta,
                    {"h", "R", "dR", "d2R", "pressure_angle", "dalpha", "normal_x", "normal_y", "pitch_x",
                     "pitch_y", "surface_x", "surface_y", "pitch_curvature", "surface_radius"},
                    [&](double t) {
                        const ProfilePoint p = cam.profile(t, e);
                        const ContactKinematics& k = p.kinematics;
                        return std::array<double, 14>{k.h, k.R, k.dR, k.d2R, k.pressure_angle(), k.dalpha,
                                                      k.normal().x(), k.normal().y(), p.pitch.x(), p.pitch.y(),
                                                      p.surface.x(), p.surface.y(), p.pitch_curvature,
                                                      p.surface_radius};
                    });
            },
            py::arg("theta"), py::arg("offset") = py::none(),
            "Profile quantities at theta (rad, scalar or array) for the nominal or a perturbed offset (m).\n"
            "Keys: h, R, dR, d2R (m, per rad), pressure_angle, dalpha (rad), normal_x/y (unit, follower\n"
            "frame: x lateral, y axial), pitch_x/y and surface_x/y (cam frame, m), pitch_curvature (1/m),\n"
            "surface_radius (m, signed: > 0 convex).")
        .def(
            "max_pressure_angle_rise",
            [](const DiskCam& c, std::optional<double> e) {
                const auto r = c.max_pressure_angle_rise(e.value_or(c.geometry().offset));
                return std::make_pair(r.theta, r.value);
            },
            py::arg("offset") = py::none(), "(theta, alpha) in rad of the largest |alpha| on the rises.")
        .def(
            "max_pressure_angle_return",
            [](const DiskCam& c, std::optional<double> e) {
                const auto r = c.max_pressure_angle_return(e.value_or(c.geometry().offset));
                return std::make_pair(r.theta, r.value);
            },
            py::arg("offset") = py::none(), "(theta, alpha) in rad of the largest |alpha| on the returns.")
        .def(
            "min_surface_radius",
            [](const DiskCam& c, std::optional<double> e, bool flanks_only) {
                const auto r = c.min_surface_radius(e.value_or(c.geometry().offset), flanks_only);
                return std::make_pair(r.theta, r.value);
            },
            py::arg("offset") = py::none(), py::arg("flanks_only") = false,
            "(theta, radius) of the smallest convex cam-surface radius of curvature (m).")
        .def("write_surface_csv", &DiskCam::write_surface_csv, py::arg("path"), py::arg("points") = 3600,
             "Write the closed cam surface as CSV (theta_rad,x_m,y_m; points + 1 rows, last = first).");
}

}  // namespace camfollower::python
