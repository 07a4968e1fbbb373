// SPDX-License-Identifier: BSD-3-Clause
// An eccentric cam: its geometric centre sits at distance epsilon from the bearing axis and turns
// with it, at u(theta) = epsilon (cos(theta + zeta), sin(theta + zeta)) in the ground frame
// (contact_geometry.hpp), zeta the direction of the offset in the cam frame. The profile itself is
// unchanged; only where it sits is.
//
// Formulations (EccentricityFormulation):
// - exact (default, physical): the contact geometry of the displaced profile. Translating roller:
//   the roller centre (e, y) lies on the displaced pitch curve; with the cam-frame pitch point
//   P(psi) = Rot(-psi) (e, R(psi)) and phi = psi - theta,
//       e cos(phi) + R(theta + phi) sin(phi) = e - u_x           (solved by Newton for phi)
//       y = u_y + (R(theta + phi) - (e - u_x) sin(phi)) / cos(phi),   alpha* = alpha(theta + phi) - phi
//   so both components of u enter the lift and the normal. Flat faces (translating or oscillating):
//   the support distance of a translated convex profile along the face normal n grows by n . u, so
//   delta += n . u is exact in u. Oscillating roller: the same n . u, first order (error
//   O(epsilon^2 / rho), rho the pitch-curve radius of curvature).
// - paper_force_{camshaft,roller,both}: the paper's literal reading (its eq 6), a force
//   K_h epsilon sin(theta + zeta) along the follower axis on the camshaft (downwards), the follower
//   (upwards) or both, with the nominal geometry. Not derived from the mechanism: a displaced centre
//   moves the contact, it does not add a force (the follower rides the run-out quasi-statically far
//   below its first mode); kept to reproduce the paper.
// Either way an optional rotating unbalance m epsilon omega^2 acts on the cam-centre DOFs.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/translating_roller.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

enum class EccentricityFormulation { exact, paper_force_camshaft, paper_force_roller, paper_force_both };

inline const char* eccentricity_formulation_name(EccentricityFormulation f) {
    switch (f) {
        case EccentricityFormulation::exact: return "exact";
        case EccentricityFormulation::paper_force_camshaft: return "paper_force_camshaft";
        case EccentricityFormulation::paper_force_roller: return "paper_force_roller";
        case EccentricityFormulation::paper_force_both: return "paper_force_both";
    }
    return "?";
}

inline EccentricityFormulation eccentricity_formulation_from(const std::string& name) {
    for (auto f : {EccentricityFormulation::exact, EccentricityFormulation::paper_force_camshaft,
                   EccentricityFormulation::paper_force_roller, EccentricityFormulation::paper_force_both})
        if (name == eccentricity_formulation_name(f)) return f;
    detail::fail(
        "eccentricity formulation must be 'exact', 'paper_force_camshaft', 'paper_force_roller' or "
        "'paper_force_both', got '",
        name, "'");
}

struct CamEccentricity {
    double radius = 0.0;  // epsilon, m (>= 0)
    double phase = 0.0;   // zeta, rad
    EccentricityFormulation formulation = EccentricityFormulation::exact;
    double unbalance_mass = 0.0;  // kg turning at radius epsilon (0: balanced)

    bool any() const { return radius != 0.0; }
    bool paper_force() const { return formulation != EccentricityFormulation::exact; }

    void validate(const std::string& who) const {
        // Bounded like any part's length: a radius near the largest double overflowed the pitch-curve
        // geometry into "theta must be finite" instead of this message.
        if (!(radius >= 0.0 && radius <= detail::max_part_length))
            detail::fail(who, " eccentricity radius must be in [0, ", detail::max_part_length, "] m, got ", radius);
        detail::require_finite(phase, (who + " eccentricity phase").c_str());
        detail::require_non_negative(unbalance_mass, (who + " unbalance mass").c_str(), "(kg)");
    }

    // Displacement of the geometric centre (ground frame) at cam angle theta, and d/dtheta.
    Eigen::Vector2d offset(double theta) const {
        return radius * Eigen::Vector2d(std::cos(theta + phase), std::sin(theta + phase));
    }
    Eigen::Vector2d offset_rate(double theta) const {
        return radius * Eigen::Vector2d(-std::sin(theta + phase), std::cos(theta + phase));
    }
};

namespace detail {

// Contact geometry from a pressure angle and the lift with their theta-rates (translating followers).
inline ContactGeometry translating_geometry(double alpha, double dalpha, double lift, double dlift) {
    const double c = std::cos(alpha), s = std::sin(alpha);
    return {Eigen::Vector2d(-s, c), Eigen::Vector2d(-c, -s) * dalpha, c, -s * dalpha, lift, dlift, c, s};
}

}  // namespace detail

// Exact contact of a translating roller with the cam displaced by u = e.offset(theta) (see above).
inline ContactGeometry eccentric_contact(const TranslatingRoller& f, const MotionProgram& program, double theta,
                                         const CamEccentricity& ecc) {
    const Eigen::Vector2d u = ecc.offset(theta), du = ecc.offset_rate(theta);
    const double e = f.offset(), e1 = e - u.x();
    FollowerMotion m = program.evaluate(theta);
    ContactKinematics k = f.kinematics(m);
    double phi = -u.x() / k.R;
    for (int it = 0;; ++it) {
        m = program.evaluate(theta + phi);
        k = f.kinematics(m);
        const double g = e * std::cos(phi) + k.R * std::sin(phi) - e1;
        const double dg = (k.dR - e) * std::sin(phi) + k.R * std::cos(phi);
        const double step = g / dg;
        phi -= step;
        if (std::abs(step) <= 1e-15 * (1.0 + std::abs(phi))) break;
        if (it == 50 || !std::isfinite(phi))
            detail::fail("eccentric cam at theta = ", radians_to_degrees(theta),
                         " deg: no roller position on the "
                         "displaced pitch curve (eccentricity radius ",
                         ecc.radius, " m is too large for this cam)");
    }
    m = program.evaluate(theta + phi);
    k = f.kinematics(m);
    const double c = std::cos(phi), s = std::sin(phi);
    // Implicit derivative of g(phi, theta) = 0; then of y and alpha* = alpha(theta + phi) - phi.
    const double g_phi = (k.dR - e) * s + k.R * c, g_theta = k.dR * s + du.x();
    const double dphi = -g_theta / g_phi;
    const double y_rel = (k.R - e1 * s) / c;
    const double dy_rel =
        ((k.dR * (1.0 + dphi) + du.x() * s - e1 * c * dphi) * c + (k.R - e1 * s) * s * dphi) / (c * c);
    const double alpha = k.pressure_angle() - phi;
    const double dalpha = k.dalpha * (1.0 + dphi) - dphi;
    return detail::translating_geometry(alpha, dalpha, u.y() + y_rel - f.pitch_base(), du.y() + dy_rel);
}

}  // namespace camfollower
