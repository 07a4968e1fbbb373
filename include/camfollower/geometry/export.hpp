// SPDX-License-Identifier: BSD-3-Clause
// Cam outline for manufacturing: the cam surface over one revolution and the path of a cutter's
// centre (milling cutter or grinding wheel of radius r_c), in the cam frame, in a chosen length unit,
// for any follower type; and a CSV writer whose header states every convention a machinist needs.
//
// Conventions (docs/followers.md): the cam turns counter-clockwise as theta grows, seen from +z of
// the right-handed ground frame (x right, y up). Cam frame X_cam = Rot(-theta) X_ground, so at
// theta = 0 the cam frame is the ground frame, and as theta grows the contact point runs clockwise
// round the cam. Sample k is at theta_k = 2 pi k / n, k = 0..n-1; the outline is closed (the last
// point joins the first).
//
// Cutter path: the surface offset outward along its unit normal (the contact normal, cam to
// follower) by r_c. For a roller follower with r_c = r_r it is the pitch curve. Outward offsetting
// never fails on a convex stretch; on a concave one of radius |rho| the offset folds over itself
// (the cutter gouges) once r_c > |rho|, so such a cutter is refused, naming the cam angle.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "camfollower/contact/contact_pair.hpp"  // Follower, the four types
#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/plane.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/units.hpp"

namespace camfollower {

struct CamOutline {
    LengthUnit unit = LengthUnit::mm;      // of surface and cutter
    std::optional<double> cutter_radius;   // m; none: no cutter path
    std::vector<double> theta;             // rad, 2 pi k / n
    std::vector<Eigen::Vector2d> surface;  // cam surface, cam frame, in `unit`
    std::vector<Eigen::Vector2d> normal;   // outward unit normal of the surface, cam frame
    std::vector<Eigen::Vector2d> cutter;   // cutter-centre path, cam frame, in `unit` (or empty)
};

// Smallest radius of curvature of the concave part of the cam surface (m, > 0) and its cam angle;
// value +inf when the surface is convex everywhere. The follower must trace the cam
// (check_undercut), which keeps the surface curvature finite and smooth.
template <class F>
AngleExtremum min_concave_radius(const MotionProgram& program, const F& follower) {
    // Concave curvature -1/rho (rho < 0 concave, +inf at an inflection: curvature 0).
    const AngleExtremum e = detail::max_over_revolution(
        program, [&](double theta) { return -1.0 / follower.profile(theta, program.evaluate(theta)).surface_radius; },
        "the cam surface curvature");
    return {e.theta, e.value > 0.0 ? 1.0 / e.value : std::numeric_limits<double>::infinity()};
}

// The cam surface (and the cutter-centre path for cutter_radius r_c >= 0, m) at `points` >= 3 cam
// angles. Throws std::invalid_argument when the follower cannot trace the program (undercut, cusp,
// 90 deg) or when the cutter is larger than the tightest concave radius of the surface.
template <class F>
CamOutline cam_outline(const F& follower, const MotionProgram& program, std::size_t points = 3600,
                       std::optional<double> cutter_radius = std::nullopt, LengthUnit unit = LengthUnit::mm) {
    if constexpr (is_barrel_follower<F>::value)
        detail::fail(F::type_name,
                     " runs in a barrel cam's groove, which has no disk outline: export its groove "
                     "(barrel_groove, geometry/barrel_groove.hpp)");
    detail::require_point_count(points, 3, "points");
    if (cutter_radius) detail::require_non_negative(*cutter_radius, "cutter_radius", "(m)");
    length_unit_spec(unit);  // validates the enumerator
    check_undercut(program, follower);
    if (cutter_radius && *cutter_radius > 0.0) {
        const AngleExtremum concave = min_concave_radius(program, follower);
        if (*cutter_radius > concave.value)
            detail::fail("cutter_radius = ", *cutter_radius,
                         " m cannot cut this cam: the surface is concave at theta = ",
                         radians_to_degrees(concave.theta), " deg with radius of curvature ", concave.value,
                         " m there, and a larger cutter gouges it; cutter_radius must be <= ", concave.value, " m");
    }
    const double scale = 1.0 / length_unit_spec(unit).metres;
    CamOutline out;
    out.unit = unit;
    out.cutter_radius = cutter_radius;
    out.theta.reserve(points);
    out.surface.reserve(points);
    out.normal.reserve(points);
    if (cutter_radius) out.cutter.reserve(points);
    for (std::size_t k = 0; k < points; ++k) {
        const double theta = two_pi * static_cast<double>(k) / static_cast<double>(points);
        const FollowerMotion m = program.evaluate(theta);
        const FollowerProfilePoint p = follower.profile(theta, m);
        const Eigen::Vector2d n = planar::to_cam_frame(theta, follower.contact(theta, m).normal);
        out.theta.push_back(theta);
        out.surface.push_back(scale * p.surface);
        out.normal.push_back(n);
        if (cutter_radius) out.cutter.push_back(scale * (p.surface + *cutter_radius * n));
    }
    return out;
}

inline CamOutline cam_outline(const Follower& follower, const MotionProgram& program, std::size_t points = 3600,
                              std::optional<double> cutter_radius = std::nullopt, LengthUnit unit = LengthUnit::mm) {
    return std::visit([&](const auto& f) { return cam_outline(f, program, points, cutter_radius, unit); }, follower);
}

// describe_follower (follower/parameters.hpp) for any type the Follower variant holds.
inline std::string describe_follower(const Follower& f, LengthUnit unit) {
    return std::visit([&](const auto& x) { return describe_follower(x, unit); }, f);
}

// The header lines of an export (without comment marks): units, rotation, zero reference, follower,
// cutter, number of points. The CSV writer prints them after "# "; the DXF writer stores them too.
template <class F>
std::vector<std::string> cam_export_notes(const F& follower, const MotionProgram& program, const CamOutline& outline) {
    using detail::concat;
    const char* u = length_unit_name(outline.unit);
    const bool oscillating = !is_translating(follower);
    const auto lift_text = [&](double h) {
        return oscillating ? concat(radians_to_degrees(h), " deg of arm rotation")
                           : concat(metres_to(outline.unit, h), " ", u);
    };
    const Segment& s = program.segments()[program.segment_index(0.0)];
    // The program tiles [0, 2 pi), so theta = 0 starts its first segment.
    const char* doing = s.lift() > 0.0 ? "starting a rise" : s.lift() < 0.0 ? "starting a return" : "on a dwell";
    const Eigen::Vector2d& zero = outline.surface.front();
    std::vector<std::string> notes{
        "camfollower cam outline for manufacturing",
        concat("units: lengths in ", u, " (", length_unit_spec(outline.unit).metres, " m), theta in rad"),
        "frame: cam frame, origin at the cam centre (camshaft axis), x and y right-handed, drawn with x right "
        "and y up (seen from +z)",
        "rotation: the cam turns counter-clockwise viewed from +z as theta grows (ground frame: "
        "X_cam = Rot(-theta) X_ground); rows therefore run clockwise round the cam",
        concat("zero reference: at theta = 0 the cam frame coincides with the ground frame; the zero mark is the "
               "contact point at theta = 0 (first row), polar angle ",
               radians_to_degrees(std::atan2(zero.y(), zero.x())), " deg from the cam frame's +x axis",
               oscillating ? "" : "; the follower axis is parallel to +y"),
        concat("follower at theta = 0: lift ", lift_text(program.evaluate(0.0).h), ", ", doing, " (segment ",
               program.segment_index(0.0) + 1, " of ", program.segments().size(), ": ", s.law.name(), " from ",
               radians_to_degrees(s.theta_start), " to ", radians_to_degrees(s.theta_end), " deg, lift ",
               lift_text(s.h_start), " to ", lift_text(s.h_end), ")"),
        concat("follower: ", describe_follower(follower, outline.unit)),
        outline.cutter_radius
            ? concat("cutter radius: ", metres_to(outline.unit, *outline.cutter_radius), " ", u,
                     "; cutter path = cutter centre = the surface offset outward along its normal by the cutter radius")
            : std::string("cutter radius: none (no cutter path)"),
        concat("points: ", outline.theta.size(), " (theta_k = 2 pi k / ", outline.theta.size(),
               "; closed: the last row joins the first)"),
    };
    return notes;
}

// The whole CSV text: "# " notes (and `extra_notes`, e.g. where a conjugate return cam is mounted),
// a column header, one row per sample (17 significant digits).
template <class F>
std::string cam_outline_csv(const F& follower, const MotionProgram& program, const CamOutline& outline,
                            const std::vector<std::string>& extra_notes = {}) {
    const char* u = length_unit_name(outline.unit);
    std::ostringstream out;
    out.precision(17);
    for (const std::string& line : cam_export_notes(follower, program, outline)) out << "# " << line << '\n';
    for (const std::string& line : extra_notes) out << "# " << line << '\n';
    out << "theta_rad,surface_x_" << u << ",surface_y_" << u;
    if (outline.cutter_radius) out << ",cutter_x_" << u << ",cutter_y_" << u;
    out << '\n';
    for (std::size_t k = 0; k < outline.theta.size(); ++k) {
        out << outline.theta[k] << ',' << outline.surface[k].x() << ',' << outline.surface[k].y();
        if (outline.cutter_radius) out << ',' << outline.cutter[k].x() << ',' << outline.cutter[k].y();
        out << '\n';
    }
    return out.str();
}

// Samples the outline and writes it as CSV to `path`, atomically (detail/atomic_file.hpp).
template <class F>
void write_cam_csv(const std::string& path, const F& follower, const MotionProgram& program, std::size_t points = 3600,
                   std::optional<double> cutter_radius = std::nullopt, LengthUnit unit = LengthUnit::mm,
                   const std::vector<std::string>& extra_notes = {}) {
    const CamOutline outline = cam_outline(follower, program, points, cutter_radius, unit);
    detail::write_file_atomically(path, cam_outline_csv(follower, program, outline, extra_notes));
}

}  // namespace camfollower
