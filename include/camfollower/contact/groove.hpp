// SPDX-License-Identifier: BSD-3-Clause
// A face groove (form closure): the roller runs between two flanks of the cam instead of being held on
// one by a spring. The inner flank is the cam surface of a force-closed cam (the contact pair's own
// contact); the outer flank is the pitch curve's parallel at r + c outward, c the groove clearance
// (groove width 2 r + c). When inertia reverses the load the roller leaves one flank, crosses the
// clearance and strikes the other: the paper's backlash, modelled on the cam side from its mechanism.
//
// Both flanks are parallel curves a normal distance 2 r + c apart, so with the inner flank's
// linearized penetration delta (follower/contact_geometry.hpp) the outer flank's is
//   delta_outer = -delta - c,   its rate -delta',   its force pushes the roller inwards (-g).
// Each flank is a unilateral Hertz contact with its own law: the outer flank is concave towards the
// roller, so for the same material its Hertz stiffness is higher than the convex inner flank's.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "camfollower/constants.hpp"
#include "camfollower/contact/hertz.hpp"
#include "camfollower/detail/extremum.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

struct Groove {
    double clearance = 0.0;           // c, m: groove width minus the roller's diameter (> 0)
    std::optional<HertzContact> law;  // the outer flank's contact law; the inner flank's when empty

    // A groove needs a roller (of radius roller_radius, m) and a clearance in (0, roller_radius): a
    // clearance of a roller's size is a unit slip (a clearance meant in mm written in m).
    void validate(const std::string& who, double roller_radius) const {
        const std::string name = who + " groove clearance";
        detail::require_positive(clearance, name.c_str(), "(m)");
        if (!(clearance < roller_radius))
            detail::fail(name, " ", clearance, " m must be below the roller radius ", roller_radius,
                         " m (a groove is the roller's diameter plus a small running clearance",
                         clearance >= 1e-3 ? "; did you mean mm?)" : ")");
        if (law) {
            detail::require_positive(law->stiffness, (who + " groove stiffness").c_str(), "(N/m^n)");
            detail::require_in_range(law->exponent, 1.0, 3.0, (who + " groove exponent").c_str());
            detail::require_non_negative(law->damping_factor, (who + " groove damping factor").c_str(), "(s/m)");
        }
    }
};

// The outer flank is the pitch curve offset outwards by r + c: where the pitch curve is concave with a
// radius below r + c the offset folds over itself (the outer flank undercuts). `pitch_curvature(theta)`
// is the pitch curve's signed curvature, 1/m, > 0 convex.
template <class PitchCurvature>
void check_outer_flank(const MotionProgram& program, const PitchCurvature& pitch_curvature, double reach,
                       const std::string& who) {
    const auto concavity = [&](double theta) { return -pitch_curvature(theta); };
    const detail::Extremum e =
        detail::maximize_piecewise(concavity, program.breakpoints(), 600, program.sampling_step());
    if (!std::isfinite(e.value)) detail::fail(who, ": the pitch curve's curvature is not finite");
    if (e.value > 0.0 && 1.0 / e.value <= reach)
        detail::fail(who, ": the groove's outer flank undercuts at theta = ", radians_to_degrees(e.x),
                     " deg: the pitch curve is concave with radius ", 1.0 / e.value,
                     " m there, which must exceed roller_radius + groove clearance = ", reach,
                     " m (reduce the roller, enlarge base_radius or soften the motion law)");
}

}  // namespace camfollower
