// SPDX-License-Identifier: BSD-3-Clause
// Disk cam with an offset translating roller follower (paper section 1.2, eqs 2-5).
//
// Conventions (SI; angles in rad):
// - Follower frame: y along the follower axis (away from the cam centre), x across it, towards the
//   side of the offset e. The roller centre sits at (x, y) = (e, R(theta)),
//   R = s0 + h(theta), s0 = sqrt((r_b + r_r)^2 - e^2) (paper eq 2).
// - Cam frame: a point (x_f, y_f) = (lateral, axial) of the follower frame is at
//   Rot(theta) * (axial, lateral) in the cam frame, which is exactly the paper's eq 5:
//   pitch = (R cos t - e sin t, R sin t + e cos t), surface = pitch - r_r (cos(t - a), sin(t - a)).
// - Pressure angle (paper eq 4, I12I24 = dR/dtheta): alpha = atan((R' - e) / R). A positive offset
//   lowers the pressure angle on the rise (R' > 0) and raises its magnitude on the return.
// - Contact normal, unit, from the cam to the roller, follower frame:
//   n = (e - R', R) / sqrt(R^2 + (R' - e)^2) = (-sin alpha, cos alpha).
// - Pitch-curve curvature (positive where convex):
//   kappa = (R^2 + (R' - e)(2R' - e) - R R'') / (R^2 + (R' - e)^2)^(3/2); surface radius
//   rho_s = 1/kappa - r_r. A convex stretch with 1/kappa <= r_r undercuts (the roller cannot follow).
// Every quantity is available for a perturbed offset e* (paper eqs 8-18) through the `offset`
// argument; the motion program is unchanged.
#pragma once

#include <cmath>
#include <cstdio>
#include <sstream>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/detail/extremum.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

struct DiskCamGeometry {
    double base_radius = 0.030;    // r_b, m (paper: 2 R_a = 60 mm)
    double roller_radius = 0.008;  // r_r, m (paper: 2 R_1 = 16 mm)
    double offset = 0.010;         // e, m
};

// What the dynamic model needs at one cam angle: cheap, no trigonometry beyond the motion law.
struct ContactKinematics {
    double h, dh, d2h;             // lift and its theta-derivatives
    double R, dR, d2R;             // roller-centre distance along the axis and theta-derivatives
    double cos_alpha, sin_alpha;   // pressure angle
    double dalpha;                 // d alpha / d theta

    double pressure_angle() const { return std::atan2(sin_alpha, cos_alpha); }
    // Unit normal from cam to roller, follower frame (x lateral, y axial).
    Eigen::Vector2d normal() const { return {-sin_alpha, cos_alpha}; }
};

// Full profile description at one cam angle (cam frame coordinates).
struct ProfilePoint {
    double theta;
    ContactKinematics kinematics;
    Eigen::Vector2d pitch;     // roller centre, cam frame
    Eigen::Vector2d surface;   // contact point on the cam, cam frame
    double pitch_curvature;    // 1/m, > 0 convex
    double surface_radius;     // m, signed: > 0 convex, < 0 concave; inf at an inflection
};

struct AngleExtremum {
    double theta;  // rad, where it occurs
    double value;  // rad or m
};

class DiskCam {
public:
    DiskCam(const DiskCamGeometry& geometry, MotionProgram program)
        : geometry_(geometry), program_(std::move(program)) {
        detail::require_length(geometry.base_radius, "base_radius");
        detail::require_length(geometry.roller_radius, "roller_radius");
        check_offset(geometry.offset, "offset");
        if (program_.min_lift() + pitch_base(geometry.offset) <= geometry.roller_radius)
            detail::fail("the motion program's lowest lift ", program_.min_lift(),
                         " m brings the roller centre inside the roller radius; min lift must be > ",
                         geometry.roller_radius - pitch_base(geometry.offset), " m");
        const AngleExtremum worst = max_pitch_curvature();
        if (worst.value * geometry.roller_radius >= 1.0)
            detail::fail("the cam profile undercuts at theta = ", radians_to_degrees(worst.theta),
                         " deg: pitch-curve radius of curvature ", 1.0 / worst.value,
                         " m must exceed roller_radius = ", geometry.roller_radius,
                         " m (reduce roller_radius, enlarge base_radius or soften the motion law)");
    }

    static DiskCam paper_default() { return DiskCam(DiskCamGeometry{}, MotionProgram::paper_default()); }

    const DiskCamGeometry& geometry() const { return geometry_; }
    const MotionProgram& program() const { return program_; }

    // s0 = sqrt((r_b + r_r)^2 - e^2): roller-centre height on the base circle.
    double pitch_base(double offset) const {
        const double rp = geometry_.base_radius + geometry_.roller_radius;
        return std::sqrt(rp * rp - offset * offset);
    }

    // |offset| must stay below r_b + r_r for the follower axis to cut the base pitch circle.
    void check_offset(double offset, const char* name) const {
        const double rp = geometry_.base_radius + geometry_.roller_radius;
        if (!(std::isfinite(offset) && std::abs(offset) < rp))
            detail::fail(name, " must satisfy |", name, "| < base_radius + roller_radius = ", rp,
                         " m, got ", offset, " m");
    }

    ContactKinematics kinematics(double theta) const { return kinematics(theta, geometry_.offset); }

    ContactKinematics kinematics(double theta, double offset) const {
        const FollowerMotion m = program_.evaluate(theta);
        return kinematics_from(m, pitch_base(offset), offset);
    }

    // Same, from an already evaluated lift (the hot path evaluates the program once per step).
    static ContactKinematics kinematics_from(const FollowerMotion& m, double s0, double offset) {
        const double R = s0 + m.h, dR = m.dh, d2R = m.d2h;
        const double p = dR - offset;  // R' - e
        const double norm2 = R * R + p * p;
        const double inv = 1.0 / std::sqrt(norm2);
        // d/dtheta atan(p / R) = (p' R - p R') / (R^2 + p^2), p' = R''
        return {m.h, m.dh, m.d2h, R, dR, d2R, R * inv, p * inv, (d2R * R - p * dR) / norm2};
    }

    ProfilePoint profile(double theta) const { return profile(theta, geometry_.offset); }

    ProfilePoint profile(double theta, double offset) const {
        check_offset(offset, "offset");
        const ContactKinematics k = kinematics(theta, offset);
        const double c = std::cos(theta), s = std::sin(theta);
        const double rr = geometry_.roller_radius;
        const Eigen::Vector2d pitch(k.R * c - offset * s, k.R * s + offset * c);
        // cos(theta - alpha), sin(theta - alpha)
        const Eigen::Vector2d towards_roller(c * k.cos_alpha + s * k.sin_alpha,
                                             s * k.cos_alpha - c * k.sin_alpha);
        const double kappa = curvature(k, offset);
        const double radius = kappa == 0.0 ? std::numeric_limits<double>::infinity() : 1.0 / kappa - rr;
        return {theta, k, pitch, pitch - rr * towards_roller, kappa, radius};
    }

    static double curvature(const ContactKinematics& k, double offset) {
        const double p = k.dR - offset;
        const double norm2 = k.R * k.R + p * p;
        return (k.R * k.R + p * (2.0 * k.dR - offset) - k.R * k.d2R) / (norm2 * std::sqrt(norm2));
    }

    // Largest pressure-angle magnitude over every rise (lift > 0) or every return (lift < 0) segment,
    // reported signed, with the cam angle where it occurs (ends included: with a large offset the
    // worst rise angle can sit where the rise leaves the base circle). Searched per smooth piece
    // (between segment ends and profile-error features), so a narrow dent is not missed.
    AngleExtremum max_pressure_angle_rise() const { return max_pressure_angle_rise(geometry_.offset); }
    AngleExtremum max_pressure_angle_return() const { return max_pressure_angle_return(geometry_.offset); }
    AngleExtremum max_pressure_angle_rise(double offset) const { return pressure_extreme(offset, true); }
    AngleExtremum max_pressure_angle_return(double offset) const { return pressure_extreme(offset, false); }

    // Largest pitch-curve curvature (1/m): the tightest convex spot, over the whole revolution or
    // over the rise and return flanks only (dwells excluded); per smooth piece, as above. The
    // constructor's undercut check uses it, so a narrow dent that undercuts is refused.
    AngleExtremum max_pitch_curvature(double offset, bool flanks_only = false) const {
        check_offset(offset, "offset");
        return max_over_pieces([&](const Segment& s) { return !(flanks_only && s.lift() == 0.0); },
                               [&](double t) { return curvature(kinematics(t, offset), offset); });
    }
    AngleExtremum max_pitch_curvature() const { return max_pitch_curvature(geometry_.offset); }

    // Smallest radius of curvature of the cam surface over its convex part (m).
    AngleExtremum min_surface_radius(double offset, bool flanks_only = false) const {
        const AngleExtremum k = max_pitch_curvature(offset, flanks_only);
        return {k.theta, 1.0 / k.value - geometry_.roller_radius};
    }
    AngleExtremum min_surface_radius() const { return min_surface_radius(geometry_.offset); }

    // n + 1 points theta_k = 2 pi k / n (k = 0..n), so the last point closes the profile.
    std::vector<ProfilePoint> sample(std::size_t n, double offset) const {
        detail::require_point_count(n, 3, "points");
        std::vector<ProfilePoint> out;
        out.reserve(n + 1);
        for (std::size_t k = 0; k <= n; ++k)
            out.push_back(profile(two_pi * static_cast<double>(k) / static_cast<double>(n), offset));
        return out;
    }
    std::vector<ProfilePoint> sample(std::size_t n) const { return sample(n, geometry_.offset); }

    // Cam surface as a CSV point list: theta_rad,x_m,y_m (cam frame), closed; written atomically
    // (detail/atomic_file.hpp). For manufacturing (units, cutter path, rotation and zero mark in the
    // header) use geometry/export.hpp.
    void write_surface_csv(const std::string& path, std::size_t n = 3600) const {
        const std::vector<ProfilePoint> points = sample(n);
        std::ostringstream out;
        out.precision(17);
        out << "theta_rad,x_m,y_m\n";
        for (const ProfilePoint& p : points) out << p.theta << ',' << p.surface.x() << ',' << p.surface.y() << '\n';
        detail::write_file_atomically(path, out.str(), "path");
    }

private:
    // Largest f over the segments `keep` accepts, located per smooth piece as the follower checks do
    // (follower/profile.hpp): each segment split further at the program's breakpoints (a profile
    // error's dent centres and edges: a dent narrower than a segment's sampling step would fall
    // between two samples), each piece sampled at least 600 times and no coarser than the program's
    // sampling step (waviness), then refined. Ties keep the earliest piece. -inf if none is kept. A
    // non-finite f is refused: a comparison would skip a NaN and report a value that is not the worst.
    template <class Keep, class F>
    AngleExtremum max_over_pieces(const Keep& keep, const F& raw) const {
        const auto f = [&](double t) {
            const double v = raw(t);
            if (!std::isfinite(v))
                detail::fail("the cam profile's geometry is not finite at theta = ", radians_to_degrees(t),
                             " deg (the lift's derivatives overflow: check the program's spans and lifts)");
            return v;
        };
        const std::vector<double> breaks = program_.breakpoints();
        const double step = program_.sampling_step();
        AngleExtremum best{0.0, -std::numeric_limits<double>::infinity()};
        std::vector<double> pieces;
        for (const Segment& s : program_.segments()) {
            if (!keep(s)) continue;
            pieces.assign(1, s.theta_start);
            for (double b : breaks)
                if (b > s.theta_start && b < s.theta_end) pieces.push_back(b);
            pieces.push_back(s.theta_end);
            const detail::Extremum e = detail::maximize_piecewise(f, pieces, 600, step);
            if (e.value > best.value) best = {e.x, e.value};
        }
        return best;
    }

    AngleExtremum pressure_extreme(double offset, bool rise) const {
        check_offset(offset, "offset");
        const AngleExtremum best =
            max_over_pieces([&](const Segment& s) { return rise ? s.lift() > 0.0 : s.lift() < 0.0; },
                            [&](double t) { return std::abs(kinematics(t, offset).pressure_angle()); });
        if (!(best.value >= 0.0))
            detail::fail(rise ? "the motion program has no rise segment"
                              : "the motion program has no return segment");
        return {best.theta, kinematics(best.theta, offset).pressure_angle()};
    }

    DiskCamGeometry geometry_;
    MotionProgram program_;
};

}  // namespace camfollower
