// SPDX-License-Identifier: BSD-3-Clause
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
// - paper_backlash > 0: the paper's literal reading of that clearance (contact/paper_backlash.hpp), the
//   rod's side imposed by the program: offset e +- b in the contact geometry and the guide spring K_rb
//   anchored on the displaced rod;
// - element_damping_ratio > 0: a dashpot on every element (six springs and the cam contact; not the
//   return spring, which carries the lift) in place of the paper's three, which leave the lateral modes at ~1e-5 of
//   critical. The dashpot rates c_e >= 0 are fitted so that every mode of the healthy mechanism on the dwell gets that
//   ratio: least squares on zeta_i = sum_e c_e (b_e . phi_i)^2 / (2 omega_i) (b_e the element's deformation vector,
//   phi_i the mass-normalized modes). Damping acts on element deformation rates only, so the follower's lift, a large
//   quasi-static motion, is not resisted (modal damping, C = M Phi diag(2 zeta omega) Phi^T M, would resist it). The
//   cam contact's dashpot enters as its Hunt-Crossley factor chi = c / F0 (F0 its static force on the dwell), the guide
//   walls' (with a clearance) as chi = c_rb / F0. paper_damped() is that preset at 3 %.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "camfollower/detail/secant.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper_parameters.hpp"

namespace camfollower::presets {

inline constexpr int paper_dofs = 7;  // y1..y4, x1..x3

}  // namespace camfollower::presets

#if CAMFOLLOWER_USE_PRECOMPILED
CAMFOLLOWER_MECHANISM_CLASS_INSTANCE(extern, camfollower::presets::paper_dofs)
#endif

namespace camfollower::presets {

struct PaperOptions {
    CamEccentricity eccentricity;              // none by default
    double guide_clearance = 0.0;              // m, radial; 0: the paper's guide spring K_rb
    double guide_wall_damping_factor = 0.0;    // chi of the wall law, s/m
    double guide_friction = 0.0;               // Coulomb coefficient at the guide
    double element_damping_ratio = 0.0;        // 0: the paper's dampers; in (0, 1): every element (above)
    double paper_backlash = 0.0;               // m; 0: off (the paper's imposed side switch, above)
    double paper_backlash_switch_width = 0.0;  // rad of cam angle the imposed switch ramps over (0: hard)

    void validate() const {
        eccentricity.validate("paper preset");
        if (guide_clearance != 0.0) detail::require_positive(guide_clearance, "guide_clearance", "(m)");
        detail::require_non_negative(guide_wall_damping_factor, "guide_wall_damping_factor", "(s/m)");
        detail::require_non_negative(guide_friction, "guide_friction");
        if (!(element_damping_ratio >= 0.0 && element_damping_ratio < 1.0))
            detail::fail("element_damping_ratio must be in [0, 1), got ", element_damping_ratio);
        detail::require_non_negative(paper_backlash, "paper_backlash", "(m)");
        detail::require_in_range(paper_backlash_switch_width, 0.0, pi, "paper_backlash_switch_width (rad)");
        if (paper_backlash > 0.0 && guide_clearance > 0.0)
            detail::fail("paper_backlash and guide_clearance are two models of the same guide clearance; give one");
        if (paper_backlash == 0.0 && paper_backlash_switch_width != 0.0)
            detail::fail("paper_backlash_switch_width needs a paper_backlash > 0");
        if (guide_clearance == 0.0 && (guide_friction != 0.0 || guide_wall_damping_factor != 0.0))
            detail::fail(
                "guide_friction and guide_wall_damping_factor need a guide_clearance > 0 (the rod touches a wall)");
    }
};

// Modal damping ratio the realistic preset's element dampers are fitted to (machine structures: 2-5 % of critical).
inline constexpr double realistic_damping_ratio = 0.03;

// Dashpot rates (N s/m) of the elements K_vs, K_hs, K_vc, K_hc, K_rb, K_f, K_rs and the cam contact,
// with the contact's static force on the dwell (N) that turns the last into a Hunt-Crossley factor.
struct PaperDampers {
    std::array<double, 8> c{};
    double contact_force = 0.0;  // 0: the contact keeps the parameters' own damping only

    static PaperDampers of_paper(const CamFollowerParameters& p) {
        return {{p.bearing_damping_vertical, p.bearing_damping_horizontal, 0.0, 0.0, 0.0, p.rod_damping, 0.0, 0.0},
                0.0};
    }
};

inline MechanismBuilder paper_spec(const CamFollowerParameters& p, const MotionProgram& program, double spring_preload,
                                   const PaperOptions& options = {}, const PaperDampers* dampers = nullptr) {
    p.validate();
    options.validate();
    // The paper's dampers, or the fitted ones (PaperDampers::fit below) when options ask for them.
    const PaperDampers d = dampers ? *dampers : PaperDampers::of_paper(p);
    const double m1 = p.camshaft_mass, m2 = p.roller_mass, m3 = p.follower_rod_mass, m4 = p.follower_mass;
    MechanismBuilder spec;
    const Eigen::Vector3d along(0.0, 1.0, 0.0), across(1.0, 0.0, 0.0);
    spec.add_dof("y1", m1, along);
    spec.add_dof("y2", m2, along);
    spec.add_dof("y3", m3, along);
    spec.add_dof("y4", m4, along);
    spec.add_dof("x1", m1, across);
    spec.add_dof("x2", m2, across);
    spec.add_dof("x3", m3, across);
    spec.add_spring("K_vs", "y1", "ground", p.bearing_stiffness_vertical, d.c[0]);
    spec.add_spring("K_hs", "x1", "ground", p.bearing_stiffness_horizontal, d.c[1]);
    spec.add_spring("K_vc", "y2", "y3", p.roller_pin_stiffness_vertical, d.c[2]);
    spec.add_spring("K_hc", "x2", "x3", p.roller_pin_stiffness_horizontal, d.c[3]);
    if (options.guide_clearance == 0.0) {
        spec.add_spring("K_rb", "x3", "ground", p.guide_stiffness, d.c[4]);
    } else {
        const double chi = options.guide_wall_damping_factor + (d.contact_force > 0.0 ? d.c[4] / d.contact_force : 0.0);
        ClearanceSpec guide{"guide",
                            {{"x3", 1.0}},
                            options.guide_clearance,
                            HertzContact{p.guide_stiffness, 1.0, chi},
                            options.guide_friction,
                            "y3"};
        spec.add_clearance(guide);
    }
    spec.add_spring("K_f", "y3", "y4", p.rod_stiffness, d.c[5]);
    spec.add_spring("K_rs", "y4", "ground", p.spring_stiffness, d.c[6], spring_preload);
    spec.set_gravity(Eigen::Vector3d(0.0, -p.gravity, 0.0));
    spec.camshaft_speed = p.omega();
    ContactPairSpec c{
        "cam",
        program,
        TranslatingRoller(p.geometry.base_radius, p.geometry.roller_radius, p.geometry.offset),
        HertzContact{p.contact_stiffness, p.contact_exponent,
                     p.contact_damping_factor() + (d.contact_force > 0.0 ? d.c[7] / d.contact_force : 0.0)},
        0.0,
        "x1",
        "y1",
        "y2",
        "x2",
        options.eccentricity,
        "ground"};
    if (options.paper_backlash > 0.0)
        c.paper_backlash = {options.paper_backlash, options.paper_backlash_switch_width, "x3", p.guide_stiffness};
    spec.add_contact(c);
    return spec;
}

inline const PaperDampers undamped_dampers{};

// Fits the eight dashpots of the healthy, undamped preset m so that its modes on the dwell have the
// ratio zeta, lowest modes first (see PaperOptions): non-negative least squares by active set (a dashpot whose
// rate comes out negative is dropped and the rest refitted), minimum-norm where undetermined.
// (A template so that its eigen solver is compiled once, in camfollower::precompiled, for the units
// linking it.)
template <int N>
PaperDampers fit_dampers(const Mechanism<N>& m, double zeta) {
    static_assert(N == paper_dofs, "the paper preset's dampers fit its own mechanism");
    using M7 = typename Mechanism<N>::Matrix;
    const auto q = m.initial_displacement();
    const Eigen::GeneralizedSelfAdjointEigenSolver<M7> eig(m.tangent_stiffness(0.0, q), m.mass());
    if (eig.info() != Eigen::Success) detail::fail("element damping: the eigen solver did not converge");
    // Deformation vectors: y1, x1, y2-y3, x2-x3, x3, y3-y4, y4, and the contact's g.
    Eigen::Matrix<double, paper_dofs, 8> B = Eigen::Matrix<double, paper_dofs, 8>::Zero();
    const int y1 = 0, y2 = 1, y3 = 2, y4 = 3, x1 = 4, x2 = 5, x3 = 6;
    B(y1, 0) = 1, B(x1, 1) = 1, B(y2, 2) = 1, B(y3, 2) = -1, B(x2, 3) = 1, B(x3, 3) = -1, B(x3, 4) = 1;
    B(y3, 5) = 1, B(y4, 5) = -1, B(y4, 6) = 1;
    auto w = m.workspace();
    m.prepare(0.0, w);
    const ContactTerms& c = w.contact(0).terms;
    for (int k = 0; k < c.count; ++k) B(c.dof[k], 7) = c.g[k];
    // Rows weighted by (omega_1 / omega_i)^3: dashpots on element deformations cannot damp every mode
    // of this chain alike (the first mode's largest deformation is the return spring's), so the fit
    // holds the lowest modes at zeta and lets the highest take more.
    Eigen::Matrix<double, paper_dofs, 8> A;
    Eigen::Matrix<double, paper_dofs, 1> target;
    const double omega_1 = std::sqrt(std::max(eig.eigenvalues()[0], 0.0));
    for (int i = 0; i < paper_dofs; ++i) {
        const double omega = std::sqrt(std::max(eig.eigenvalues()[i], 0.0));
        if (!(omega > 0.0)) detail::fail("element damping: mode ", i + 1, " has no stiffness");
        const double weight = std::pow(omega_1 / omega, 3);
        for (int e = 0; e < 8; ++e) {
            const double b = B.col(e).dot(eig.eigenvectors().col(i));
            A(i, e) = weight * b * b / (2.0 * omega);
        }
        target[i] = weight * zeta;
    }
    // The return spring carries the follower's lift: a dashpot there would resist the motion the cam
    // imposes (up to ~0.6 m/s at 750 rpm), not a vibration. It keeps none.
    std::array<bool, 8> free;
    free.fill(true);
    free[6] = false;
    Eigen::Matrix<double, 8, 1> rates = Eigen::Matrix<double, 8, 1>::Zero();
    for (int pass = 0; pass < 8; ++pass) {
        Eigen::MatrixXd Af(paper_dofs, 0);
        std::vector<int> columns;
        for (int e = 0; e < 8; ++e)
            if (free[std::size_t(e)]) columns.push_back(e);
        Af.resize(paper_dofs, Eigen::Index(columns.size()));
        for (std::size_t j = 0; j < columns.size(); ++j) Af.col(Eigen::Index(j)) = A.col(columns[j]);
        const Eigen::VectorXd x = Af.completeOrthogonalDecomposition().solve(target);
        rates.setZero();
        int worst = -1;
        for (std::size_t j = 0; j < columns.size(); ++j) {
            rates[columns[j]] = x[Eigen::Index(j)];
            if (x[Eigen::Index(j)] < 0.0 && (worst < 0 || x[Eigen::Index(j)] < rates[worst])) worst = columns[j];
        }
        if (worst < 0) break;
        free[std::size_t(worst)] = false;
        rates[worst] = 0.0;
    }
    PaperDampers d;
    for (int e = 0; e < 8; ++e) d.c[std::size_t(e)] = std::max(rates[e], 0.0);
    d.contact_force = m.static_contact_force(0.0, q, 0);
    return d;
}
#if CAMFOLLOWER_USE_PRECOMPILED
extern template PaperDampers fit_dampers<paper_dofs>(const Mechanism<paper_dofs>&, double);
#endif

// The preset with its calibrated preload: P solves P + K_rs y4(P) = K_rs delta_rs by secant steps
// (affine in P for the linear contact law, nearly so otherwise), on the healthy mechanism, so that
// every defect case has the same spring.
inline Mechanism<paper_dofs> paper(const CamFollowerParameters& p = {},
                                   const MotionProgram& program = MotionProgram::paper_default(),
                                   const PaperOptions& options = {}) {
    p.validate();
    const double target = p.spring_stiffness * p.spring_preload_deflection;
    const int y4 = 3;
    // P = K_rs delta_rs / (1 - K_rs / K_chain) for the series stiffness K_chain of the parts between the
    // spring and the ground along the contact normal (affine case; with the offset the normal leans, so
    // the lateral parts count too): no positive, bounded preload when that chain is about as soft as
    // the spring.
    const auto unbalanced = [&](double P) {
        detail::fail(
            "the return spring cannot be balanced on the dwell: spring_stiffness = ", p.spring_stiffness,
            " N/m at spring_preload_deflection = ", p.spring_preload_deflection, " m needs a preload of ", P,
            " N (allowed: (0, ", detail::max_force,
            "] N); the parts that hold the roller against the cam "
            "(contact_stiffness, rod_stiffness, roller_pin_stiffness_vertical, roller_pin_stiffness_horizontal, "
            "guide_stiffness, bearing_stiffness_vertical, bearing_stiffness_horizontal: in series along the "
            "contact normal) are about as soft as the spring or softer: stiffen them or soften "
            "spring_stiffness");
    };
    double terms = target;  // the residual's rounding follows its terms
    auto residual = [&](double P) {
        if (!(std::abs(P) <= detail::max_force)) unbalanced(P);
        const double spring =
            p.spring_stiffness *
            Mechanism<paper_dofs>(paper_spec(p, program, P, {}, &undamped_dampers)).initial_displacement()[y4];
        terms = std::abs(P) + std::abs(spring) + target;
        return P + spring - target;
    };
    const detail::SecantRoot root = detail::secant_root(residual, target, 1e-12 * target);
    if (!(std::abs(root.residual) <= 1e-9 * terms))
        throw ConvergenceError(detail::concat("spring preload calibration did not converge: spring force ",
                                              target + root.residual, " N against K_rs delta_rs = ", target, " N"));
    if (!(root.x > 0.0)) unbalanced(root.x);
    if (options.element_damping_ratio == 0.0) return Mechanism<paper_dofs>(paper_spec(p, program, root.x, options));
    const PaperDampers fitted = fit_dampers(
        Mechanism<paper_dofs>(paper_spec(p, program, root.x, {}, &undamped_dampers)), options.element_damping_ratio);
    return Mechanism<paper_dofs>(paper_spec(p, program, root.x, options, &fitted));
}

// The paper's mechanism with realistic damping: a dashpot on every element, fitted so that every mode
// has `ratio` of critical on the dwell (default 3 %; see PaperOptions).
inline Mechanism<paper_dofs> paper_damped(const CamFollowerParameters& p = {},
                                          const MotionProgram& program = MotionProgram::paper_default(),
                                          PaperOptions options = {}, double ratio = realistic_damping_ratio) {
    options.element_damping_ratio = ratio;
    return paper(p, program, options);
}

}  // namespace camfollower::presets
