// The paper's 7-DOF cam-follower model (Tounsi et al., docs/model.md) as a preset of the mechanism
// builder: disk cam, offset translating roller follower, camshaft on bearings, roller on its pin,
// follower rod in its guide, follower top on the return spring.
//
// DOFs (paper order): y1 camshaft, y2 roller, y3 follower rod, y4 follower top (along the follower
// axis); x1 camshaft, x2 roller, x3 rod (across it). The return spring's preload P is calibrated so
// that at the static equilibrium on the dwell (theta = 0) the spring force is K_rs delta_rs.
#pragma once

#include <cmath>

#include "camfollower/detail/secant.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/parameters.hpp"

namespace camfollower::presets {

inline constexpr int paper_dofs = 7;  // y1..y4, x1..x3

inline MechanismBuilder paper_spec(const CamFollowerParameters& p, const MotionProgram& program, double spring_preload) {
    p.validate();
    MechanismBuilder spec;
        const Eigen::Vector3d along(0.0, 1.0, 0.0), across(1.0, 0.0, 0.0);
    spec.add_dof("y1", p.camshaft_mass, along);
    spec.add_dof("y2", p.roller_mass, along);
    spec.add_dof("y3", p.follower_rod_mass, along);
    spec.add_dof("y4", p.follower_mass, along);
    spec.add_dof("x1", p.camshaft_mass, across);
    spec.add_dof("x2", p.roller_mass, across);
    spec.add_dof("x3", p.follower_rod_mass, across);
    spec.add_spring("K_vs", "y1", "ground", p.bearing_stiffness_vertical, p.bearing_damping_vertical);
    spec.add_spring("K_hs", "x1", "ground", p.bearing_stiffness_horizontal, p.bearing_damping_horizontal);
    spec.add_spring("K_vc", "y2", "y3", p.roller_pin_stiffness_vertical);
    spec.add_spring("K_hc", "x2", "x3", p.roller_pin_stiffness_horizontal);
    spec.add_spring("K_rb", "x3", "ground", p.guide_stiffness);
    spec.add_spring("K_f", "y3", "y4", p.rod_stiffness, p.rod_damping);
    spec.add_spring("K_rs", "y4", "ground", p.spring_stiffness, 0.0, spring_preload);
    spec.set_gravity(Eigen::Vector3d(0.0, -p.gravity, 0.0));
    spec.camshaft_speed = p.omega();
    ContactPairSpec c{"cam",
                      program,
                      TranslatingRoller(p.geometry.base_radius, p.geometry.roller_radius, p.geometry.offset),
                      HertzContact{p.contact_stiffness, p.contact_exponent, p.contact_damping_factor()},
                      0.0,
                      "x1",
                      "y1",
                      "y2",
                      "x2"};
    spec.add_contact(c);
    return spec;
}

// The preset with its calibrated preload: P solves P + K_rs y4(P) = K_rs delta_rs by secant steps
// (affine in P for the linear contact law, nearly so otherwise).
inline Mechanism<paper_dofs> paper(const CamFollowerParameters& p = {},
                          const MotionProgram& program = MotionProgram::paper_default()) {
    const double target = p.spring_stiffness * p.spring_preload_deflection;
    const int y4 = 3;
    auto residual = [&](double P) {
        return P + p.spring_stiffness * Mechanism<paper_dofs>(paper_spec(p, program, P)).initial_displacement()[y4] - target;
    };
    const detail::SecantRoot root = detail::secant_root(residual, target, 1e-12 * target);
    if (!(std::abs(root.residual) <= 1e-9 * target))
        throw ConvergenceError(detail::concat("spring preload calibration did not converge: spring force ",
                                              target + root.residual, " N against K_rs delta_rs = ", target, " N"));
    return Mechanism<paper_dofs>(paper_spec(p, program, root.x));
}

}  // namespace camfollower::presets
