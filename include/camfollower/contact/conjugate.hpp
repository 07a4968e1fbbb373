// SPDX-License-Identifier: BSD-3-Clause
// Conjugate cams: two disk cams on one shaft, each pushing one roller (or face) of one follower, the
// lift cam in the lifting sense and the return cam against it, so the follower is held both ways
// without a spring (form closure; a desmodromic valve gear is one).
//
// The follower's DOF q is the lift cam's follower coordinate. The return cam's follower is a second
// contact pair on the same DOF, mapped s_r = H + b - q (ContactPairSpec::follower_ratio = -1,
// follower_offset = H + b): for a rigid follower touching both cams the two lifts add up to the
// constant H, h_r(theta) = H - h(theta), and b opens a play between the cams (b > 0) or closes it
// into an interference that preloads both contacts (b < 0). H is the lift program's highest lift, so
// the return cam's base circle is where the lift cam is at its top.
//   - A translating follower: the return roller sits across the cam centre, pushing the other way,
//     so its pair's frame is turned by pi (frame_angle): its cam is mounted at phase + pi on the shaft,
//     and its follower's offset is measured in that turned frame (on the lift roller's axis: -offset).
//   - An oscillating follower (a bell crank): both arms on one pivot, the return arm lifting in the
//     opposite sense (turn), both frames the ground frame. The angle between the arms follows from
//     the two geometries (arm_angle()).
// The return program defaults to the lift program's complement (built-in laws); one given instead
// (a table, a spline) must add up with the lift program to a constant within 1e-9 of the stroke.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/error.hpp"

namespace camfollower {

struct ConjugateCams {
    std::string name;                             // the pair: contacts "<name>.lift" and "<name>.return"
    MotionProgram program;                        // the lift cam's program: the follower's motion
    Follower follower;                            // the lift cam's follower
    Follower return_follower;                     // the return cam's: the same kind (see above)
    std::optional<MotionProgram> return_program;  // default: program.complement(H)
    HertzContact law;                             // both contacts' law, unless return_law is given
    std::optional<HertzContact> return_law;
    double phase = 0.0;     // rad: the lift cam's angle = omega t + phase
    double backlash = 0.0;  // m or rad as the lift: play between the cams (> 0) or interference (< 0)
    std::string cam_x = "ground", cam_y = "ground", follower_dof, lateral = "ground", cam_twist = "ground";

    static constexpr const char* lift_suffix = ".lift";
    static constexpr const char* return_suffix = ".return";

    // H: the sum of the two lifts (the lift program's highest lift with the default return program).
    double total_lift() const {
        return return_program ? program.evaluate(0.0).h + return_program->evaluate(0.0).h : program.max_lift();
    }

    // The two contact pairs, lift cam first, checked as a pair (names, kinds, pivots, conjugacy).
    std::vector<ContactPairSpec> contacts() const {
        const std::string who = "conjugate cams '" + name + "'";
        detail::require_name(name, "conjugate cams");
        const bool translating = is_translating(follower);
        if (is_barrel(follower) || is_barrel(return_follower))
            detail::fail(who,
                         ": conjugate cams are disk cams; a barrel cam is form-closed by its groove (give the "
                         "contact a groove instead)");
        if (translating != is_translating(return_follower))
            detail::fail(who, ": the lift and return followers must both be translating or both oscillating (",
                         follower_type_name(follower), ", ", follower_type_name(return_follower), ")");
        const double stroke = program.max_lift() - program.min_lift();
        if (!(std::isfinite(backlash) && std::abs(backlash) < stroke))
            detail::fail(who, ": backlash must be finite and smaller than the stroke ", stroke, " (|backlash| < ",
                         stroke, "), got ", backlash);
        if (!translating) check_bell_crank(who);
        const double H = total_lift();
        MotionProgram back = return_program ? *return_program : program.complement(H);
        if (return_program) check_conjugate(who, back, H);
        ContactPairSpec lift{name + lift_suffix, program, follower,          law,      phase, cam_x, cam_y,
                             follower_dof,       lateral, CamEccentricity{}, cam_twist};
        ContactPairSpec ret{name + return_suffix,
                            std::move(back),
                            return_follower,
                            return_law ? *return_law : law,
                            phase,
                            cam_x,
                            cam_y,
                            follower_dof,
                            lateral,
                            CamEccentricity{},
                            cam_twist};
        ret.follower_ratio = -1.0;
        ret.follower_offset = H + backlash;
        ret.frame_angle = translating ? pi : 0.0;
        return {std::move(lift), std::move(ret)};
    }

    // An oscillating pair's angle from the lift arm to the return arm (rad, counter-clockwise), fixed
    // on the bell crank: phi_r - phi with both followers on their cams at once.
    double arm_angle() const {
        return std::visit(
            [&](const auto& a, const auto& b) -> double {
                using A = std::decay_t<decltype(a)>;
                using B = std::decay_t<decltype(b)>;
                if constexpr (!A::translating && !B::translating) {
                    // s = 0 on the lift cam: the lift arm at its start angle; the return cam at H + b.
                    FollowerMotion up{};
                    up.h = total_lift() + backlash;
                    return b.arm_angle(up) - a.start_angle();
                } else {
                    detail::fail("conjugate cams '", name, "': arm_angle is for oscillating followers");
                }
            },
            follower, return_follower);
    }

private:
    void check_bell_crank(const std::string& who) const {
        std::visit(
            [&](const auto& a, const auto& b) {
                using A = std::decay_t<decltype(a)>;
                using B = std::decay_t<decltype(b)>;
                if constexpr (!A::translating && !B::translating) {
                    if ((a.pivot() - b.pivot()).norm() > 1e-9 * (1.0 + a.pivot().norm()))
                        detail::fail(who, ": both arms turn about one pivot; the lift arm's is (", a.pivot().x(), ", ",
                                     a.pivot().y(), ") m, the return arm's (", b.pivot().x(), ", ", b.pivot().y(),
                                     ") m");
                    if (a.turn() == b.turn())
                        detail::fail(who,
                                     ": the return arm must lift in the opposite sense (turn) to the lift arm, "
                                     "both are ",
                                     arm_turn_name(a.turn()));
                }
            },
            follower, return_follower);
    }

    // h + h_r constant: the rollers keep their distance. Sampled at 3600 angles and each segment end.
    void check_conjugate(const std::string& who, const MotionProgram& back, double H) const {
        const double stroke = std::max(program.max_lift() - program.min_lift(), 1e-12);
        double worst = 0.0, at = 0.0;
        std::vector<double> angles = program.breakpoints();
        const std::vector<double> more = back.breakpoints();
        angles.insert(angles.end(), more.begin(), more.end());
        for (int i = 0; i < 3600; ++i) angles.push_back(two_pi * i / 3600.0);
        for (double t : angles) {
            const double miss = std::abs(program.evaluate(t).h + back.evaluate(t).h - H);
            if (miss > worst) worst = miss, at = t;
        }
        if (worst > 1e-9 * stroke)
            detail::fail(who, ": the return program is not conjugate to the lift program: h + h_return = ",
                         program.evaluate(at).h + back.evaluate(at).h, " at ", radians_to_degrees(at), " deg but ", H,
                         " at 0 deg (off by ", worst, ", more than 1e-9 of the stroke ", stroke,
                         "); the two lifts must add up to a constant, as the rollers keep their distance");
    }
};

}  // namespace camfollower
