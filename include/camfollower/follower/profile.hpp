// SPDX-License-Identifier: BSD-3-Clause
// Cam profile as seen by one follower type, and the sampled design checks that work for any type:
// largest pressure angle, tightest convex surface radius, and the undercut / cusp test.
//
// A follower type F used with these templates provides
//   FollowerProfilePoint profile(double theta, const FollowerMotion& m) const;
//   double follower_radius() const;   // radius of its contact element: roller radius, +inf for a face
//
// Why the effective radius: the roller test "pitch radius of curvature <= roller radius on a convex
// stretch" and the flat-face test "surface radius <= 0" are both "1 / (1/rho_cam + 1/rho_follower)
// <= 0". That quantity is smooth and finite through inflections (roller: r_r (1 - r_r kappa_pitch);
// face: rho_cam), so an extremum search on it is reliable where 1/kappa is not.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "camfollower/detail/extremum.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/laws.hpp"  // pi
#include "camfollower/motion/program.hpp"

namespace camfollower {

// Where a checked quantity is worst over the revolution, and its value there.
struct AngleExtremum {
    double theta;  // rad, where it occurs
    double value;  // rad or m
};

struct FollowerProfilePoint {
    double theta;                    // cam angle, rad
    Eigen::Vector2d surface;         // contact point on the cam surface, cam frame, m
    Eigen::Vector2d reference;       // roller centre, or the face's reference point, cam frame, m
    Eigen::Vector2d contact_ground;  // the same contact point, ground frame, m
    double surface_radius;           // cam surface radius of curvature, m: > 0 convex, < 0 concave,
                                     // +inf at an inflection
    double effective_radius;         // 1 / (1/surface_radius + 1/follower_radius), m; <= 0: undercut
                                     // (roller) or cusp (face)
    double pressure_angle;           // rad, see contact_geometry.hpp
};

namespace detail {

// Largest value of f(theta) over the revolution, located per smooth piece of the program (segments,
// split further at a profile error's dents, which would otherwise fall between samples; kinks sit on
// the piece ends). detail::maximize skips a NaN silently (NaN > x is false), so a non-finite sample
// is recorded and refused here: an undefined geometry must not pass a check.
[[noreturn]] inline void fail_not_finite(const char* what, double theta) {
    fail(what, " is not finite at theta = ", radians_to_degrees(theta),
         " deg: the follower geometry is undefined "
         "there (check the motion program's speed and the follower parameters)");
}

template <class F>
AngleExtremum max_over_revolution(const MotionProgram& program, const F& f, const char* what) {
    bool finite = true;
    double bad_theta = 0.0;
    const auto guarded = [&](double theta) {
        const double v = f(theta);
        if (!std::isfinite(v) && finite) finite = false, bad_theta = theta;
        return v;
    };
    const Extremum e = maximize_piecewise(guarded, program.breakpoints(), 600, program.sampling_step());
    if (!finite) fail_not_finite(what, bad_theta);
    return {e.x, e.value};
}

}  // namespace detail

// Pressure angle of largest magnitude over the revolution, reported signed, with its cam angle.
template <class Follower>
AngleExtremum max_pressure_angle(const MotionProgram& program, const Follower& follower) {
    const auto angle = [&](double theta) { return follower.profile(theta, program.evaluate(theta)).pressure_angle; };
    const AngleExtremum e = detail::max_over_revolution(
        program, [&](double theta) { return std::abs(angle(theta)); }, "the pressure angle");
    return {e.theta, angle(e.theta)};
}

// Smallest effective contact radius over the revolution (m), with its cam angle.
template <class Follower>
AngleExtremum min_effective_radius(const MotionProgram& program, const Follower& follower) {
    const AngleExtremum e = detail::max_over_revolution(
        program, [&](double theta) { return -follower.profile(theta, program.evaluate(theta)).effective_radius; },
        "the cam surface curvature");
    return {e.theta, -e.value};
}

// Smallest radius of curvature of the convex cam surface (m), with its cam angle. The effective
// radius decreases monotonically with the convex surface curvature, so both are least at the same
// theta; a value <= 0 means undercut (roller) or cusp (face).
template <class Follower>
AngleExtremum min_surface_radius(const MotionProgram& program, const Follower& follower) {
    const AngleExtremum e = min_effective_radius(program, follower);
    return {e.theta, follower.profile(e.theta, program.evaluate(e.theta)).surface_radius};
}

// Throws std::invalid_argument, naming theta in degrees and the offending value and limit, when the
// follower cannot trace the program: a roller undercuts (pitch-curve radius of curvature <= roller
// radius on a convex stretch), a face meets a cusp (surface radius <= 0), the pressure angle reaches
// 90 deg, or the geometry is not finite somewhere.
// One sampling pass serves both checks (model construction runs them for every contact; a Monte-Carlo
// study builds thousands of models).
template <class Follower>
void check_undercut(const MotionProgram& program, const Follower& follower) {
    const char* bad = nullptr;  // the first quantity found not finite (NaN would pass the search)
    double bad_theta = 0.0;
    const auto both = [&](double theta) {
        const FollowerProfilePoint p = follower.profile(theta, program.evaluate(theta));
        const std::array<double, 2> v{-p.effective_radius, std::abs(p.pressure_angle)};
        if (!bad && !std::isfinite(v[0])) bad = "the cam surface curvature", bad_theta = theta;
        if (!bad && !std::isfinite(v[1])) bad = "the pressure angle", bad_theta = theta;
        return v;
    };
    const std::array<detail::Extremum, 2> e =
        detail::maximize_piecewise_together<2>(both, program.breakpoints(), 600, program.sampling_step());
    if (bad) detail::fail_not_finite(bad, bad_theta);
    const AngleExtremum tightest{e[0].x, -e[0].value};
    if (!(tightest.value > 0.0)) {
        const FollowerProfilePoint p = follower.profile(tightest.theta, program.evaluate(tightest.theta));
        const double rf = follower.follower_radius();
        if (std::isinf(rf))
            detail::fail("the cam surface has a cusp at theta = ", radians_to_degrees(tightest.theta),
                         " deg: surface radius of curvature ", p.surface_radius,
                         " m must be > 0 (enlarge base_radius or soften the motion law)");
        detail::fail("the cam profile undercuts at theta = ", radians_to_degrees(tightest.theta),
                     " deg: pitch-curve radius of curvature ", p.surface_radius + rf,
                     " m must exceed roller_radius = ", rf,
                     " m (reduce roller_radius, enlarge base_radius or soften the motion law)");
    }
    const double steepest_theta = e[1].x;
    const AngleExtremum steepest{steepest_theta,
                                 follower.profile(steepest_theta, program.evaluate(steepest_theta)).pressure_angle};
    if (std::abs(steepest.value) >= 0.5 * pi)
        detail::fail("the pressure angle reaches ", radians_to_degrees(steepest.value),
                     " deg at theta = ", radians_to_degrees(steepest.theta),
                     " deg: its magnitude must stay below 90 deg (the follower would jam)");
}

}  // namespace camfollower
