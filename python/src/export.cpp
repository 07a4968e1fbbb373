// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/geometry/export.hpp: the cam outline and cutter path for
// manufacturing, its CSV writer, the length-unit table and the atomic file writer (which the Python
// DXF writer reuses, so every output file is written the same way).
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/geometry/export.hpp"
#include "camfollower/units.hpp"

namespace camfollower::python {

namespace {

// Python ints of any sign arrive here, so a negative count is a ValueError naming the parameter.
std::size_t point_count(long long points) {
    detail::require_point_count(points, 3, "points");
    return static_cast<std::size_t>(points);
}

py::array_t<double> column(const std::vector<Eigen::Vector2d>& v, int axis) {
    py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
    double* d = a.mutable_data();
    for (std::size_t k = 0; k < v.size(); ++k) d[k] = v[k][axis];
    return a;
}

}  // namespace

void bind_export(py::module_& m) {
    m.def(
        "length_units",
        [] {
            py::dict d;
            for (const LengthUnitSpec& s : length_units()) d[s.name] = s.metres;
            return d;
        },
        "Length units accepted by the exports: {name: metres per unit} (m, mm, um, inch = 0.0254 m).");
    m.def(
        "cam_outline",
        [](const py::object& follower, const MotionProgram& program, long long points,
           std::optional<double> cutter_radius, const std::string& unit) {
            const Follower f = follower_from(follower);
            const std::size_t n = point_count(points);
            const LengthUnit u = length_unit_from_name(unit);
            CamOutline o;
            std::vector<std::string> notes;
            {
                py::gil_scoped_release release;
                o = cam_outline(f, program, n, cutter_radius, u);
                notes = cam_export_notes(f, program, o);
            }
            py::dict d;
            d["theta"] = py::array_t<double>(static_cast<py::ssize_t>(o.theta.size()), o.theta.data());
            d["surface_x"] = column(o.surface, 0);
            d["surface_y"] = column(o.surface, 1);
            d["normal_x"] = column(o.normal, 0);
            d["normal_y"] = column(o.normal, 1);
            if (cutter_radius) {
                d["cutter_x"] = column(o.cutter, 0);
                d["cutter_y"] = column(o.cutter, 1);
            }
            d["unit"] = unit;
            d["cutter_radius"] = cutter_radius;
            d["notes"] = notes;
            return d;
        },
        py::arg("follower"), py::arg("program"), py::arg("points") = 3600, py::arg("cutter_radius") = py::none(),
        py::arg("unit") = "mm",
        "Cam surface over one revolution (theta_k = 2 pi k / points, cam frame, lengths in `unit`), its outward unit\n"
        "normals, and the cutter-centre path for cutter_radius (m; the surface offset outward by it). Keys: theta,\n"
        "surface_x/y, normal_x/y, cutter_x/y (with a cutter), unit, cutter_radius, notes (the file header lines).\n"
        "Raises ValueError on undercut, or a cutter larger than the tightest concave radius (named with its angle).");
    m.def(
        "write_cam_csv",
        [](const std::string& path, const py::object& follower, const MotionProgram& program, long long points,
           std::optional<double> cutter_radius, const std::string& unit) {
            const Follower f = follower_from(follower);
            const std::size_t n = point_count(points);
            const LengthUnit u = length_unit_from_name(unit);
            py::gil_scoped_release release;
            std::visit([&](const auto& x) { write_cam_csv(path, x, program, n, cutter_radius, u); }, f);
        },
        py::arg("path"), py::arg("follower"), py::arg("program"), py::arg("points") = 3600,
        py::arg("cutter_radius") = py::none(), py::arg("unit") = "mm",
        "Write the cam outline as CSV (commented header with units, rotation, zero reference, follower, cutter,\n"
        "points; then theta_rad,surface_x_<unit>,surface_y_<unit>[,cutter_x_<unit>,cutter_y_<unit>]), atomically.");
    m.def(
        "write_file_atomically",
        [](const std::string& path, const py::bytes& content, const std::vector<std::string>& protect) {
            const std::string data = content;
            py::gil_scoped_release release;
            detail::write_file_atomically(path, data, "path", protect);
        },
        py::arg("path"), py::arg("content"), py::arg("protect") = std::vector<std::string>{},
        "Replace or create `path` with `content` (bytes) atomically: a uniquely named temporary in the same\n"
        "folder, then a rename; nothing is left behind on failure. Refuses (ValueError) a target that is a\n"
        "directory, FIFO, socket, device or symbolic link, a read-only file, a path holding a NUL, and any\n"
        "of `protect` (input files the run read).");
    m.def(
        "check_output_target",
        [](const std::string& path, const std::vector<std::string>& protect) {
            detail::require_output_target(path, "path", protect);
        },
        py::arg("path"), py::arg("protect") = std::vector<std::string>{},
        "Raise ValueError if write_file_atomically would refuse `path` (checked before a long run).");
}

}  // namespace camfollower::python
