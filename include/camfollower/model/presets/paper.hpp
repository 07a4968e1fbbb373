// The paper's 7-DOF cam-follower model (Tounsi et al., docs/model.md) as a preset of the mechanism
// builder: disk cam, offset translating roller follower, camshaft on bearings, roller on its pin,
// follower rod in its guide, follower top on the return spring.
//
// DOFs (paper order): y1 camshaft, y2 roller, y3 follower rod, y4 follower top (along the follower
// axis); x1 camshaft, x2 roller, x3 rod (across it). The return spring's preload P is calibrated so
// that at the static equilibrium on the dwell (theta = 0) the spring force is K_rs delta_rs.
//
// PaperOptions add the defects as their mechanisms (contact/eccentricity.hpp, contact/clearance.hpp)
// and the damping:
// - eccentricity: the cam's centre displaced (exact), or the paper's literal force (named formulation);
// - guide_clearance > 0: the rod x3 in its guide with a radial gap, walls of stiffness K_rb (the
//   paper's guide spring becomes the wall), optional wall damping and Coulomb friction on y3;
// - modal_damping_ratio > 0: every mode damped at that ratio (about the static equilibrium at
//   theta = 0) in place of the paper's element dampers, whose values leave the lateral modes at
//   ~1e-5 of critical. paper_damped() is that preset at 3 %.
#pragma once

#include <cmath>

#include "camfollower/detail/secant.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/parameters.hpp"

namespace camfollower::presets {

inline constexpr int paper_dofs = 7;  // y1..y4, x1..x3

struct PaperOptions {
    CamEccentricity eccentricity;          // none by default
    double guide_clearance = 0.0;          // m, radial; 0: the paper's guide spring K_rb
    double guide_wall_damping_factor = 0.0;  // chi of the wall law, s/m
    double guide_friction = 0.0;           // Coulomb coefficient at the guide
    double modal_damping_ratio = 0.0;      // 0: the paper's element dampers; in (0, 1): every mode

    void validate() const {
        eccentricity.validate("paper preset");
        if (guide_clearance != 0.0) detail::require_positive(guide_clearance, "guide_clearance", "(m)");
        detail::require_non_negative(guide_wall_damping_factor, "guide_wall_damping_factor", "(s/m)");
        detail::require_non_negative(guide_friction, "guide_friction");
        if (!(modal_damping_ratio >= 0.0 && modal_damping_ratio < 1.0))
            detail::fail("modal_damping_ratio must be in [0, 1), got ", modal_damping_ratio);
        if (guide_clearance == 0.0 && (guide_friction != 0.0 || guide_wall_damping_factor != 0.0))
            detail::fail("guide_friction and guide_wall_damping_factor need a guide_clearance > 0 (the rod touches a wall)");
    }
};

// Modal damping ratio of the realistic preset (machine structures: 2-5 % of critical).
inline constexpr double realistic_damping_ratio = 0.03;

inline MechanismBuilder paper_spec(const CamFollowerParameters& p, const MotionProgram& program, double spring_preload,
                                   const PaperOptions& options = {}) {
    p.validate();
    options.validate();
    const bool modal = options.modal_damping_ratio > 0.0;
    const double d = modal ? 0.0 : 1.0;  // the paper's element dampers, unless modal damping replaces them
    MechanismBuilder spec;
        const Eigen::Vector3d along(0.0, 1.0, 0.0), across(1.0, 0.0, 0.0);
    spec.add_dof("y1", p.camshaft_mass, along);
    spec.add_dof("y2", p.roller_mass, along);
    spec.add_dof("y3", p.follower_rod_mass, along);
    spec.add_dof("y4", p.follower_mass, along);
    spec.add_dof("x1", p.camshaft_mass, across);
    spec.add_dof("x2", p.roller_mass, across);
    spec.add_dof("x3", p.follower_rod_mass, across);
    spec.add_spring("K_vs", "y1", "ground", p.bearing_stiffness_vertical, d * p.bearing_damping_vertical);
    spec.add_spring("K_hs", "x1", "ground", p.bearing_stiffness_horizontal, d * p.bearing_damping_horizontal);
    spec.add_spring("K_vc", "y2", "y3", p.roller_pin_stiffness_vertical);
    spec.add_spring("K_hc", "x2", "x3", p.roller_pin_stiffness_horizontal);
    if (options.guide_clearance == 0.0) {
        spec.add_spring("K_rb", "x3", "ground", p.guide_stiffness);
    } else {
        ClearanceSpec guide{"guide", {{"x3", 1.0}}, options.guide_clearance,
                            HertzContact{p.guide_stiffness, 1.0, options.guide_wall_damping_factor},
                            options.guide_friction, "y3"};
        spec.add_clearance(guide);
    }
    spec.add_spring("K_f", "y3", "y4", p.rod_stiffness, d * p.rod_damping);
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
                      "x2",
                      options.eccentricity};
    spec.add_contact(c);
    if (modal) spec.set_modal_damping({options.modal_damping_ratio});
    return spec;
}

// The preset with its calibrated preload: P solves P + K_rs y4(P) = K_rs delta_rs by secant steps
// (affine in P for the linear contact law, nearly so otherwise), on the healthy mechanism, so that
// every defect case has the same spring.
inline Mechanism<paper_dofs> paper(const CamFollowerParameters& p = {},
                                   const MotionProgram& program = MotionProgram::paper_default(),
                                   const PaperOptions& options = {}) {
    const double target = p.spring_stiffness * p.spring_preload_deflection;
    const int y4 = 3;
    auto residual = [&](double P) {
        return P + p.spring_stiffness * Mechanism<paper_dofs>(paper_spec(p, program, P)).initial_displacement()[y4] - target;
    };
    const detail::SecantRoot root = detail::secant_root(residual, target, 1e-12 * target);
    if (!(std::abs(root.residual) <= 1e-9 * target))
        throw ConvergenceError(detail::concat("spring preload calibration did not converge: spring force ",
                                              target + root.residual, " N against K_rs delta_rs = ", target, " N"));
    return Mechanism<paper_dofs>(paper_spec(p, program, root.x, options));
}

// The paper's mechanism with realistic damping: every mode at `ratio` of critical (default 3 %).
inline Mechanism<paper_dofs> paper_damped(const CamFollowerParameters& p = {},
                                          const MotionProgram& program = MotionProgram::paper_default(),
                                          PaperOptions options = {}, double ratio = realistic_damping_ratio) {
    options.modal_damping_ratio = ratio;
    return paper(p, program, options);
}

}  // namespace camfollower::presets
