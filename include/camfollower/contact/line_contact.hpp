// SPDX-License-Identifier: BSD-3-Clause
// Contact stress between the roller (or flat face) and the cam, from geometry and elastic constants.
//
// Straight roller: two parallel cylinders touching along a line of length L (Johnson, Contact
// Mechanics, ch. 4). With the contact modulus E* and the relative radius R,
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,   1/R = 1/R1 + 1/R2   (a concave body has R < 0),
// the pressure is a half-ellipse across the strip of half-width b:
//   b = sqrt(4 F R / (pi L E*)),   p_max = 2 F / (pi b L) = sqrt(F E* / (pi L R)).
// A line contact has no unique approach (it depends on the bodies' size), so for the dynamics we
// offer Palmgren's empirical roller law instead (palmgren_law below).
//
// Crowned roller (crown radius R_c across the width): the contact is a point contact that spreads
// into an ellipse. Hamrock & Brewe's curve fits (Hamrock & Dowson, Ball Bearing Lubrication, 1981)
// replace the elliptic integrals; with alpha = Ry/Rx >= 1 (Ry across the width, Rx along rolling),
//   k = a/b ~ 1.0339 alpha^0.636,  E(e) ~ 1.0003 + 0.5968/alpha,  F(e) ~ 1.5277 + 0.6023 ln alpha,
//   a = (6 k^2 E W R / (pi E'))^(1/3),  b = (6 E W R / (pi k E'))^(1/3),   E' = 2 E*,
//   delta = F [ (9 / (2 E R)) (W / (pi k E'))^2 ]^(1/3),   p_max = 3 W / (2 pi a b),
// with 1/R = 1/Rx + 1/Ry. The fits hold for 1 <= alpha <= 100 (Hamrock & Brewe's range): there they
// give a within 4.2 %, b 2.0 %, p_max 2.2 % and delta 5.4 % of exact elliptical Hertz (the worst at
// alpha = 1 or 100; at alpha = 1, k 3.4 %, E 1.7 %, F 2.7 % off the exact 1, pi/2, pi/2). Beyond 100
// (a long crown on a small roller: a 1 m crown on R = 9.5 mm gives 105) the error grows: a +5.7 %,
// p_max -2.8 %, delta -5.0 % at 150; +6.9 %, -3.3 %, -5.9 % at 200; +15 %, -6.8 %, -12 % at 1000.
// ContactStress::radius_ratio reports alpha so a caller can tell (Python warns beyond 100).
//
// SI units: m, N, Pa.
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "camfollower/contact/hertz.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/motion/laws.hpp"  // pi
#include "camfollower/motion/program.hpp"

namespace camfollower {

// Upper end of the radius ratio alpha = Ry/Rx (>= 1) for which the Hamrock-Brewe fits are made.
inline constexpr double hamrock_brewe_max_ratio = 100.0;

struct Elastic {
    double youngs_modulus = 210e9;  // E, Pa
    double poisson_ratio = 0.3;     // nu, 0 <= nu < 0.5 (0.5 is incompressible: no contact modulus)

    static Elastic steel() { return {210e9, 0.3}; }

    void validate(const char* who = "material") const {
        detail::require_positive(youngs_modulus, detail::concat(who, " youngs_modulus").c_str(), "(Pa)");
        if (!(std::isfinite(poisson_ratio) && poisson_ratio >= 0.0 && poisson_ratio < 0.5))
            detail::fail(who, " poisson_ratio must be in [0, 0.5), got ", poisson_ratio);
    }
    // (1 - nu^2) / E: this body's share of the contact compliance, 1/Pa.
    double compliance() const { return (1.0 - poisson_ratio * poisson_ratio) / youngs_modulus; }
};

// Contact modulus E*, Pa: the two bodies' compliances add like springs in series.
inline double effective_modulus(const Elastic& a, const Elastic& b) {
    a.validate("first body:");
    b.validate("second body:");
    return 1.0 / (a.compliance() + b.compliance());
}

// Relative radius of two bodies with radii r1, r2 (m; > 0 convex, < 0 concave, inf flat). Must be
// > 0 and finite: <= 0 means the concave body is tighter than the convex one (no contact from
// outside), inf means two planes (no Hertz contact).
inline double relative_radius(double r1, double r2) {
    if (std::isnan(r1) || std::isnan(r2) || r1 == 0.0 || r2 == 0.0)
        detail::fail("radii of curvature must be non-zero and not NaN (inf: flat), got ", r1, " m and ", r2, " m");
    const double curvature = 1.0 / r1 + 1.0 / r2;
    if (!(curvature > 0.0))
        detail::fail(
            "the contact's effective radius must be > 0 (the cam surface is more concave than the "
            "roller, or both bodies are flat): radii ",
            r1, " m and ", r2, " m give 1/R = ", curvature, " 1/m");
    return 1.0 / curvature;
}

// Result of one stress evaluation. For the straight roller, semi_axis = L/2 (the line's half-length)
// and approach is NaN (not defined by the 2-D theory).
struct ContactStress {
    double half_width;        // b: contact semi-axis along the rolling direction, m
    double semi_axis;         // a: contact semi-axis across the roller width, m
    double max_pressure;      // p_max, Pa
    double approach;          // delta: mutual approach of distant points, m (crowned only)
    double effective_radius;  // R in the rolling plane (Rx), m
    // Crowned: alpha = Ry/Rx (or Rx/Ry, >= 1) at which the fits were evaluated; beyond
    // hamrock_brewe_max_ratio they leave their range. NaN for a straight roller.
    double radius_ratio = std::numeric_limits<double>::quiet_NaN();
};

struct LineContact {
    double length = 0.01;                                           // roller width L, m
    Elastic roller, cam;                                            // materials (steel by default)
    double crown_radius = std::numeric_limits<double>::infinity();  // m; inf: straight roller

    bool crowned() const { return std::isfinite(crown_radius); }

    void validate() const {
        detail::require_positive(length, "roller width (length)", "(m)");
        roller.validate("roller:");
        cam.validate("cam:");
        if (!(crown_radius > 0.0))  // inf allowed (straight)
            detail::fail("crown_radius must be > 0 m (inf: straight roller), got ", crown_radius);
    }

    // Stress for a normal force (N, >= 0) between the roller of radius r1 and the cam of radius r2
    // (m, signed as relative_radius). With r2 = inf, r1 is the relative radius itself.
    ContactStress stress(double force, double r1, double r2 = std::numeric_limits<double>::infinity()) const {
        validate();
        detail::require_non_negative(force, "contact force", "(N)");
        const double R = relative_radius(r1, r2);
        const double E = effective_modulus(roller, cam);
        const double nan = std::numeric_limits<double>::quiet_NaN();
        if (!crowned()) {
            const double b = std::sqrt(4.0 * force * R / (pi * length * E));
            // sqrt(F E* / (pi L R)) equals 2F / (pi b L) and stays finite at F = 0.
            return {b, 0.5 * length, std::sqrt(force * E / (pi * length * R)), nan, R, nan};
        }
        // Crowned: across the width only the crown curves (the cam is straight along its axis).
        const double Rx = R, Ry = crown_radius;
        const bool wide = Ry >= Rx;                     // ellipse's long axis across the width (the usual case)
        const double alpha = wide ? Ry / Rx : Rx / Ry;  // the fits need alpha >= 1: swap otherwise
        const double k = 1.0339 * std::pow(alpha, 0.636);
        const double Ee = 1.0003 + 0.5968 / alpha;
        const double Fe = 1.5277 + 0.6023 * std::log(alpha);
        const double Rc = 1.0 / (1.0 / Rx + 1.0 / Ry);
        const double Ep = 2.0 * E;
        const double major = std::cbrt(6.0 * k * k * Ee * force * Rc / (pi * Ep));
        const double minor = std::cbrt(6.0 * Ee * force * Rc / (pi * k * Ep));
        const double w = force / (pi * k * Ep);
        const double delta = Fe * std::cbrt(9.0 / (2.0 * Ee * Rc) * w * w);
        const double p = force > 0.0 ? 3.0 * force / (2.0 * pi * major * minor) : 0.0;
        return {wide ? minor : major, wide ? major : minor, p, delta, Rx, alpha};
    }
};

// Palmgren's empirical approach of a straight steel roller (Palmgren, Ball and Roller Bearing
// Engineering): delta[mm] = 3.84e-5 Q[N]^0.9 / L[mm]^0.8, i.e. Q = K delta^(10/9). Returns K in SI,
// N/m^(10/9), for the roller width L in m. Steel on steel only: it ignores the elastic constants.
inline double palmgren_stiffness(double length) {
    detail::require_positive(length, "roller width (length)", "(m)");
    const double L_mm = 1e3 * length;
    const double K_mm = std::pow(std::pow(L_mm, 0.8) / 3.84e-5, 10.0 / 9.0);  // N/mm^(10/9)
    return K_mm * std::pow(1e3, 10.0 / 9.0);                                  // delta_mm = 1e3 delta_m
}

// Palmgren's law as a contact law for the dynamics (an alternative to a hand-picked K_h).
inline HertzContact palmgren_law(double length, double damping_factor = 0.0) {
    detail::require_non_negative(damping_factor, "damping_factor", "(s/m)");
    return {palmgren_stiffness(length), 10.0 / 9.0, damping_factor};
}

// Stress at cam angle theta (rad) for contact force F (N) with any follower type: the roller (or the
// face, follower_radius() = inf) against the cam surface's signed radius of curvature there.
template <class Follower>
ContactStress profile_stress(const LineContact& contact, const MotionProgram& program, const Follower& follower,
                             double theta, double force) {
    const FollowerProfilePoint p = follower.profile(theta, program.evaluate(theta));
    try {
        return contact.stress(force, follower.follower_radius(), p.surface_radius);
    } catch (const std::invalid_argument& e) {
        detail::fail("at theta = ", radians_to_degrees(theta), " deg: ", e.what());
    }
}

// The same over many angles; force has one entry (constant) or one per angle.
template <class Follower>
std::vector<ContactStress> profile_stress(const LineContact& contact, const MotionProgram& program,
                                          const Follower& follower, const std::vector<double>& theta,
                                          const std::vector<double>& force) {
    if (force.size() != 1 && force.size() != theta.size())
        detail::fail("force must have one value or one per angle (", theta.size(), "), got ", force.size());
    std::vector<ContactStress> out;
    out.reserve(theta.size());
    for (std::size_t i = 0; i < theta.size(); ++i)
        out.push_back(profile_stress(contact, program, follower, theta[i], force.size() == 1 ? force[0] : force[i]));
    return out;
}

}  // namespace camfollower
