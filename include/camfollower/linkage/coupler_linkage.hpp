// SPDX-License-Identifier: BSD-3-Clause
// A cam-driven linkage: the follower's swing arm drives an output link through a coupler, the output a
// slider on a fixed line (swing arm - coupler - slider) or a rocker about a fixed pivot (a four-bar).
//
// Model (model/elements/pin_joint_element.hpp): the coupler is a rigid planar body with its own three
// DOFs "<name>.x", "<name>.y" (m) and "<name>.angle" (rad), its mass on both translations and its
// moment of inertia about its centre of mass (mid-length) on the rotation, so its inertia is exact
// and the mechanism's mass matrix stays constant; the effective mass the arm sees then changes with
// the configuration as the linkage's does. The coupler's ends are joined to the arm's pin and to the
// output's pin by pin joints: isotropic spring-dampers between the two points ("<name>.input",
// "<name>.output"; their stiffness the joints' and links' compliance in series). Stiff joints hold
// the exact linkage kinematics. q = 0 is the configuration the linkage is assembled in at the arm's
// reference angle, on the chosen branch.
//
// The rigid linkage's output as a function of the arm's displacement is closed-form (output(), for
// double or Taylor3: its SVAJ), and so is its inverse (input(): the backward solution, from a wanted
// output to the arm's motion, hence the cam's lift).
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>

#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/arm_turn.hpp"
#include "camfollower/linkage/planar_point.hpp"
#include "camfollower/linkage/taylor.hpp"

namespace camfollower {

// Two points of two links held together by a stiff isotropic spring-damper, N/m and N s/m.
struct PinJointSpec {
    std::string name;
    PlanarPoint a, b;
    double stiffness = 0.0, damping = 0.0;

    void validate() const {
        detail::require_name(name, "pin joint");
        const std::string who = "pin joint '" + name + "'";
        a.validate(who + " end a");
        b.validate(who + " end b");
        detail::require_positive(stiffness, (who + " stiffness").c_str(), "(N/m)");
        detail::require_non_negative(damping, (who + " damping").c_str(), "(N s/m)");
    }
};

struct CouplerLinkage {
    enum class Output { slider, rocker };

    std::string name;
    // The input: the swing arm turning about arm_pivot (the follower's DOF, rad, lifting in the sense
    // arm_turn as seen in this plane), its coupler pin at arm_length (m) and at the angle arm_angle
    // (rad) at q = 0.
    std::string arm_dof;
    Eigen::Vector2d arm_pivot = Eigen::Vector2d::Zero();
    double arm_length = 0.0, arm_angle = 0.0;
    ArmTurn arm_turn = ArmTurn::counter_clockwise;
    // The coupler: pin-to-pin length (m), mass (kg) and moment of inertia about its centre of mass
    // at mid-length (kg m^2).
    double coupler_length = 0.0, coupler_mass = 0.0, coupler_inertia = 0.0;
    // The output: a slider (output_dof in m along the line through output_origin at the angle
    // output_direction, rad) or a rocker (output_dof in rad about the pivot output_origin, pin at
    // output_length m, its DOF positive in the sense output_turn).
    Output output = Output::slider;
    std::string output_dof;
    Eigen::Vector2d output_origin = Eigen::Vector2d::Zero();
    double output_direction = 0.0, output_length = 0.0;
    ArmTurn output_turn = ArmTurn::counter_clockwise;
    // Which of the two assemblies: +1 or -1 (slider: the pin ahead of or behind the foot of the
    // perpendicular from the arm's pin along the line's direction; rocker: the output pin left or
    // right of the line from the arm's pin to the rocker's pivot).
    int branch = 1;
    // Both pin joints: stiffness (N/m) and damping (N s/m).
    double joint_stiffness = 0.0, joint_damping = 0.0;

    std::string who() const { return "linkage '" + name + "'"; }
    void validate() const {
        detail::require_name(name, "linkage");
        const std::string w = who();
        if (arm_dof.empty() || output_dof.empty()) detail::fail(w, ": arm_dof and output_dof must name DOFs");
        if (arm_dof == output_dof) detail::fail(w, ": arm_dof and output_dof are both '", arm_dof, "'");
        const auto length = [&](double x, const char* what) {
            if (!(std::isfinite(x) && x >= detail::min_part_length && x <= detail::max_part_length))
                detail::fail(w, ": ", what, " must be in [", detail::min_part_length, ", ", detail::max_part_length,
                             "] m, got ", x, " m");
        };
        length(arm_length, "arm_length");
        length(coupler_length, "coupler_length");
        if (output == Output::rocker) length(output_length, "output_length");
        if (!(arm_pivot.allFinite() && output_origin.allFinite()))
            detail::fail(w, ": arm_pivot and output_origin must be finite");
        for (double a : {arm_angle, output_direction})
            if (!std::isfinite(a)) detail::fail(w, ": arm_angle and output_direction must be finite");
        if (!(branch == 1 || branch == -1)) detail::fail(w, ": branch must be +1 or -1, got ", branch);
        // The coupler is a body with DOFs of its own: without mass or inertia they would have none.
        detail::require_positive(coupler_mass, (w + " coupler_mass").c_str(), "(kg)");
        detail::require_positive(coupler_inertia, (w + " coupler_inertia").c_str(), "(kg m^2)");
        detail::require_positive(joint_stiffness, (w + " joint_stiffness").c_str(), "(N/m)");
        detail::require_non_negative(joint_damping, (w + " joint_damping").c_str(), "(N s/m)");
        output_pin(0.0);  // it assembles at the reference
    }

    // The arm's pin at the arm's displacement q (rad).
    template <class T>
    void arm_pin(const T& q, T& x, T& y) const {
        using std::cos;
        using std::sin;
        const T a = T(arm_angle) + turn_sign(arm_turn) * q;
        x = T(arm_pivot.x()) + arm_length * cos(a);
        y = T(arm_pivot.y()) + arm_length * sin(a);
    }

    // The rigid linkage's output displacement (slider: m along its line from the reference; rocker:
    // rad from the reference) at the arm's displacement q (rad). Refuses a q where it cannot close.
    template <class T>
    T output_displacement(const T& q) const {
        T d = output_coordinate(q) - output_coordinate(T(0.0));
        if (output == Output::slider) return d;
        set_value(d, std::remainder(value(d), two_pi));  // the rocker's turn nearest the reference
        return turn_sign(output_turn) * d;
    }
    double output_at(double q) const { return output_displacement(q); }

    // The output pin at the arm's displacement q (m), for the assembly.
    Eigen::Vector2d output_pin(double q) const {
        double ax, ay;
        arm_pin(q, ax, ay);
        const double c = output_coordinate(q);
        if (output == Output::slider)
            return output_origin + c * Eigen::Vector2d(std::cos(output_direction), std::sin(output_direction));
        return output_origin + output_length * Eigen::Vector2d(std::cos(c), std::sin(c));
    }
    Eigen::Vector2d arm_pin_at(double q) const {
        double x, y;
        arm_pin(q, x, y);
        return {x, y};
    }

    // The backward solution: the arm's displacement (rad) that puts the output at displacement s from
    // its reference, on the branch the arm's reference angle sits on.
    double input_at(double s) const {
        const Eigen::Vector2d B = output_pin_from_displacement(s), O = arm_pivot;
        // The arm's pin on both circles |A - O| = arm_length and |A - B| = coupler_length.
        const Eigen::Vector2d d = B - O;
        const double D = d.norm(), r = arm_length, L = coupler_length;
        const double a = (r * r - L * L + D * D) / (2.0 * D), h2 = r * r - a * a;
        if (!(D > 0.0) || !(h2 >= 0.0))
            detail::fail(who(), ": the output at ", s, " from its reference cannot be reached (the coupler of ", L,
                         " m does not reach the arm's circle)");
        const Eigen::Vector2d m = O + a / D * d, n(-d.y() / D, d.x() / D);
        const Eigen::Vector2d A0 = arm_pin_at(0.0);
        // The side of the line O-B the reference pin is on (checked at the reference configuration).
        const Eigen::Vector2d B0 = output_pin(0.0), d0 = B0 - O;
        const double side = (d0.x() * (A0 - O).y() - d0.y() * (A0 - O).x()) >= 0.0 ? 1.0 : -1.0;
        const Eigen::Vector2d A = m + side * std::sqrt(h2) * n;
        const double angle = std::atan2(A.y() - O.y(), A.x() - O.x());
        double q = turn_sign(arm_turn) * (angle - arm_angle);
        q = std::remainder(q, two_pi);  // the displacement nearest the reference
        return q;
    }

private:
    // Slider: the pin's position along the line (m from output_origin); rocker: the rocker's angle
    // (rad) in the plane frame.
    template <class T>
    T output_coordinate(const T& q) const {
        using std::atan2;
        using std::sqrt;
        T ax, ay;
        arm_pin(q, ax, ay);
        const double L = coupler_length;
        if (output == Output::slider) {
            const double ux = std::cos(output_direction), uy = std::sin(output_direction);
            const T px = ax - output_origin.x(), py = ay - output_origin.y();
            const T along = px * ux + py * uy, across = px * (-uy) + py * ux;
            const T disc = T(L * L) - across * across;
            if (!(value(disc) >= 0.0))
                detail::fail(who(), ": the coupler of ", L, " m cannot reach the slider's line at arm displacement ",
                             value(q), " rad (the pin is ", std::abs(value(across)), " m from it)");
            return along + double(branch) * sqrt(disc);
        }
        // Rocker: the output pin on circles |B - A| = L and |B - O2| = r2.
        const T dx = T(output_origin.x()) - ax, dy = T(output_origin.y()) - ay;
        const T D2 = dx * dx + dy * dy, D = sqrt(D2);
        const double r2 = output_length;
        const T a = (T(L * L - r2 * r2) + D2) / (2.0 * D);
        const T h2 = T(L * L) - a * a;
        if (!(value(h2) >= 0.0))
            detail::fail(who(), ": the four-bar cannot close at arm displacement ", value(q), " rad (coupler ", L,
                         " m and rocker ", r2, " m do not span the ", value(D),
                         " m between the arm's pin and the rocker's pivot)");
        const T h = sqrt(h2);
        const T bx = ax + (a * dx - double(branch) * h * dy) / D, by = ay + (a * dy + double(branch) * h * dx) / D;
        return atan2(by - output_origin.y(), bx - output_origin.x());
    }
    Eigen::Vector2d output_pin_from_displacement(double s) const {
        const double c = output_coordinate(0.0) + (output == Output::slider ? s : turn_sign(output_turn) * s);
        if (output == Output::slider)
            return output_origin + c * Eigen::Vector2d(std::cos(output_direction), std::sin(output_direction));
        return output_origin + output_length * Eigen::Vector2d(std::cos(c), std::sin(c));
    }
    static double value(double x) { return x; }
    static double value(const Taylor3& x) { return x.v; }
    static void set_value(double& x, double v) { x = v; }
    static void set_value(Taylor3& x, double v) { x.v = v; }
};

}  // namespace camfollower
