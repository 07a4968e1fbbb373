// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/geometry/export.hpp: the cam outline and cutter path for
// manufacturing, its CSV writer, the length-unit table and the atomic file writer (which the Python
// DXF writer reuses, so every output file is written the same way).
#include <optional>
#include <type_traits>
#include <utility>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/geometry/barrel_groove.hpp"
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

// f(the barrel follower) for a BarrelRoller or BarrelArmRoller; a disk cam's follower is refused.
template <class Fn>
auto with_barrel(const Follower& follower, Fn&& f) {
    using Result = decltype(f(std::declval<const BarrelRoller&>()));
    return std::visit(
        [&](const auto& x) -> Result {
            using F = std::decay_t<decltype(x)>;
            if constexpr (is_barrel_follower<F>::value) return f(x);
            else
                detail::fail("follower: a barrel cam's groove needs BarrelRoller or BarrelArmRoller, got ",
                             F::type_name, " (a disk cam: export its outline with cam_outline)");
        },
        follower);
}

py::array_t<double> rows(const std::vector<std::vector<BarrelWallPoint>>& walls, double BarrelWallPoint::*field) {
    const py::ssize_t n = static_cast<py::ssize_t>(walls.size()), m = n ? static_cast<py::ssize_t>(walls[0].size()) : 0;
    py::array_t<double> a({n, m});
    auto d = a.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i)
        for (py::ssize_t k = 0; k < m; ++k)
            d(i, k) = walls[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)].*field;
    return a;
}

py::array_t<double> column3(const std::vector<Eigen::Vector3d>& v, int axis) {
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
           std::optional<double> cutter_radius, const std::string& unit, const std::vector<std::string>& notes) {
            const Follower f = follower_from(follower);
            const std::size_t n = point_count(points);
            const LengthUnit u = length_unit_from_name(unit);
            py::gil_scoped_release release;
            std::visit([&](const auto& x) { write_cam_csv(path, x, program, n, cutter_radius, u, notes); }, f);
        },
        py::arg("path"), py::arg("follower"), py::arg("program"), py::arg("points") = 3600,
        py::arg("cutter_radius") = py::none(), py::arg("unit") = "mm", py::arg("notes") = std::vector<std::string>{},
        "Write the cam outline as CSV (commented header with units, rotation, zero reference, follower, cutter,\n"
        "points, then any `notes`; then "
        "theta_rad,surface_x_<unit>,surface_y_<unit>[,cutter_x_<unit>,cutter_y_<unit>]),\n"
        "atomically.");
    m.def(
        "barrel_groove",
        [](const py::object& follower, const MotionProgram& program, long long points, double clearance,
           const std::string& roller) {
            const Follower f = follower_from(follower);
            const std::size_t n = point_count(points);
            const BarrelRollerShape shape = barrel_roller_shape_from(roller);
            BarrelGroove g;
            {
                py::gil_scoped_release release;
                g = with_barrel(f, [&](const auto& x) { return barrel_groove(x, program, n, clearance, shape); });
            }
            py::dict d;
            d["theta"] = py::array_t<double>(static_cast<py::ssize_t>(g.theta.size()), g.theta.data());
            d["radii"] = py::array_t<double>(static_cast<py::ssize_t>(g.radii.size()), g.radii.data());
            d["centre_angle"] = column(g.centre, 0);
            d["centre_z"] = column(g.centre, 1);
            d["lift_angle"] = rows(g.lift, &BarrelWallPoint::angle);
            d["lift_z"] = rows(g.lift, &BarrelWallPoint::axial);
            d["back_angle"] = rows(g.back, &BarrelWallPoint::angle);
            d["back_z"] = rows(g.back, &BarrelWallPoint::axial);
            d["pressure_angle"] = rows(g.lift, &BarrelWallPoint::pressure_angle);
            d["cutter_cross"] = column3(g.cutter, 0);
            d["cutter_axial"] = column3(g.cutter, 1);
            d["cutter_plunge"] = column3(g.cutter, 2);
            d["clearance"] = g.clearance;
            d["roller"] = barrel_roller_shape_name(g.shape);
            return d;
        },
        py::arg("follower"), py::arg("program"), py::arg("points") = 3600, py::arg("clearance") = 0.0,
        py::arg("roller") = "cylindrical",
        "A barrel cam's groove (BarrelRoller or BarrelArmRoller) at theta_k = 2 pi k / points, SI units: the exact\n"
        "walls (envelopes of the roller's positions) for a 'cylindrical' or the ideal 'tapered' roller at the\n"
        "radii (top, pitch, bottom). Keys: theta, radii (m), centre_angle/centre_z (roller centre at the pitch\n"
        "radius: position round the cam in rad, the roller's station being at theta, and height in m), lift_angle,\n"
        "lift_z, back_angle, back_z (3 x points: the lifting flank and the opposite one, clearance m away),\n"
        "pressure_angle (3 x points, rad, on the lifting flank), cutter_cross/cutter_axial/cutter_plunge (m: the\n"
        "4-axis machining path of a cutter shaped as the roller, larger by clearance/2), clearance, roller.\n"
        "Raises ValueError naming the radius and angle where the roller undercuts or jams.");
    m.def(
        "write_barrel_groove_csv",
        [](const std::string& path, const py::object& follower, const MotionProgram& program, long long points,
           double clearance, const std::string& roller, const std::string& unit) {
            const Follower f = follower_from(follower);
            const std::size_t n = point_count(points);
            const BarrelRollerShape shape = barrel_roller_shape_from(roller);
            const LengthUnit u = length_unit_from_name(unit);
            py::gil_scoped_release release;
            with_barrel(f, [&](const auto& x) {
                write_barrel_groove_csv(path, x, program, n, clearance, shape, u);
                return 0;
            });
        },
        py::arg("path"), py::arg("follower"), py::arg("program"), py::arg("points") = 3600, py::arg("clearance") = 0.0,
        py::arg("roller") = "cylindrical", py::arg("unit") = "mm",
        "Write a barrel cam's groove as CSV, atomically: commented header (units, frame, radii, roller, machining\n"
        "axes), then per cam angle the roller centre, both flanks and the pressure angle at the top, pitch and\n"
        "bottom radii (angles in deg, lengths in `unit`) and the machining path.");
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
