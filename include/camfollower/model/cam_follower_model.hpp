// SPDX-License-Identifier: BSD-3-Clause
// The paper's 7-DOF flexible cam-follower model (section 1.1; as implemented: docs/model.md). The
// same model is built from the mechanism parts by presets::paper (model/presets/paper.hpp); this class
// stays for the paper's imposed defects until they are rebuilt on those parts.
//
// q = <y1, y2, y3, y4, x1, x2, x3> (paper order): y along the follower axis, x across it towards the
// offset side. Bodies: 1 camshaft on its bearings, 2 roller centre, 3 follower rod at its guide,
// 4 follower top (spring seat). Displacements are absolute, measured from the unloaded configuration
// in which the roller just touches the base circle, so y2, y3, y4 carry the lift h(theta).
//
// Linear network (assembled once into constant M, C, K):
//   y1-ground K_vs, C_vs;  x1-ground K_hs, C_hs;  y2-y3 K_vc;  x2-x3 K_hc;  x3-ground K_rb;
//   y3-y4 K_f, C_f;  y4-ground K_rs (return spring).
// Cam-roller contact (nonlinear, unilateral), normal n = (-sin a, cos a) from cam to roller:
//   delta = (u1 - u2) . n + h cos a + de_c(t) = g(t)^T q + h cos a + de_c,
//   g = d delta / dq: g_y1 = cos a, g_y2 = -cos a, g_x1 = -sin a, g_x2 = sin a;
//   generalized contact force F_c g on the left-hand side (pushes the roller along +n).
// Return spring: its force on y4 is -(P + K_rs y4), with the preload P set so that at the static
// equilibrium on the dwell (theta = 0, no defects) the spring force is exactly K_rs delta_rs.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "camfollower/contact/hertz.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/detail/force_inline.hpp"
#include "camfollower/detail/secant.hpp"
#include "camfollower/geometry/disk_cam.hpp"
#include "camfollower/model/defects.hpp"
#include "camfollower/model/network.hpp"
#include "camfollower/model/parameters.hpp"

namespace camfollower {

class CamFollowerModel {
public:
    static constexpr int dofs = 7;
    enum Dof : int { y1 = 0, y2 = 1, y3 = 2, y4 = 3, x1 = 4, x2 = 5, x3 = 6 };
    using Vector = Eigen::Matrix<double, dofs, 1>;
    using Matrix = Eigen::Matrix<double, dofs, dofs>;

    // Everything that depends on time only: evaluated once per step, reused by every Newton
    // iteration.
    struct TimeContext {
        double t, theta;
        ContactKinematics kinematics;  // at the effective offset
        double offset;                 // effective offset e + defects, m
        double side;                   // backlash side s in [-1, 1]
        Vector g, g_dot;               // d delta / dq and its time derivative
        double delta0, delta0_dot;     // delta = g^T q + delta0
        Vector external;               // applied forces (preload, gravity, backlash excitation)
        double pressure_angle() const { return kinematics.pressure_angle(); }
    };

    struct Nonlinear {
        Vector force;       // F_c g - external: every term not in M, C, K (left-hand side)
        double delta;       // penetration, m
        double delta_dot;   // m/s
        ContactResponse contact;
    };

    explicit CamFollowerModel(const CamFollowerParameters& parameters = {},
                              MotionProgram program = MotionProgram::paper_default(),
                              const Defects& defects = {})
        : parameters_(validated(parameters)),
          defects_(validated(defects)),
          cam_(parameters.geometry, std::move(program)),
          backlash_side_(cam_.program(), defects.backlash_switch_width) {
        const CamFollowerParameters& p = parameters_;
        // The defects move the offset to e + eccentricity cos(.) +- backlash: it must stay a
        // possible offset for the pitch circle.
        const double reach = std::abs(p.geometry.offset) + defects_.eccentricity + defects_.backlash;
        const double rp = p.geometry.base_radius + p.geometry.roller_radius;
        if (!(reach < rp))
            detail::fail("eccentricity + backlash = ", defects_.eccentricity + defects_.backlash,
                         " m with |offset| = ", std::abs(p.geometry.offset), " m make the effective offset reach ", reach,
                         " m: it must stay below base_radius + roller_radius = ", rp, " m");
        network_.set_mass(y1, p.camshaft_mass, "camshaft (y1)");
        network_.set_mass(y2, p.roller_mass, "roller (y2)");
        network_.set_mass(y3, p.follower_rod_mass, "follower rod (y3)");
        network_.set_mass(y4, p.follower_mass, "follower top (y4)");
        network_.set_mass(x1, p.camshaft_mass, "camshaft (x1)");
        network_.set_mass(x2, p.roller_mass, "roller (x2)");
        network_.set_mass(x3, p.follower_rod_mass, "follower rod (x3)");
        network_.connect(y1, ground, p.bearing_stiffness_vertical, p.bearing_damping_vertical, "K_vs");
        network_.connect(x1, ground, p.bearing_stiffness_horizontal, p.bearing_damping_horizontal, "K_hs");
        network_.connect(y2, y3, p.roller_pin_stiffness_vertical, 0.0, "K_vc");
        network_.connect(x2, x3, p.roller_pin_stiffness_horizontal, 0.0, "K_hc");
        network_.connect(x3, ground, p.guide_stiffness, 0.0, "K_rb");
        network_.connect(y3, y4, p.rod_stiffness, p.rod_damping, "K_f");
        network_.connect(y4, ground, p.spring_stiffness, 0.0, "K_rs");
        M_ = network_.mass_matrix();
        C_ = network_.damping_matrix();
        K_ = network_.stiffness_matrix();
        contact_ = {p.contact_stiffness, p.contact_exponent, p.contact_damping_factor()};
        omega_ = p.omega();
        s0_ = cam_.pitch_base(p.geometry.offset);
        for (int k = 0; k < 4; ++k) gravity_force_[k] = -p.gravity * M_(k, k);
        calibrate_preload();
        initial_state_ = static_equilibrium(0.0);
    }

    const CamFollowerParameters& parameters() const { return parameters_; }
    const Defects& defects() const { return defects_; }
    const DiskCam& cam() const { return cam_; }
    const LumpedNetwork<dofs>& network() const { return network_; }
    const Matrix& mass_matrix() const { return M_; }
    const Matrix& damping_matrix() const { return C_; }
    const Matrix& stiffness_matrix() const { return K_; }

    // --- The second-order-system contract (core/system.hpp) ---
    // Workspace: the time terms of the step, and the contact-loss intervals of the run (path memory,
    // updated after every accepted step, so no loss shorter than a step between two records is missed).
    struct Workspace {
        TimeContext context;
        bool in_contact = true;
        double loss_start = 0.0;
        std::vector<std::pair<double, double>> contact_loss;  // [start, end) times
        mutable Nonlinear last{};  // of the last force() call, reused by tangent() and accepted()
    };
    int size() const { return dofs; }
    const Matrix& mass() const { return M_; }
    const Matrix& damping() const { return C_; }
    const Matrix& stiffness() const { return K_; }
    Vector initial_displacement() const { return initial_state_; }
    Workspace workspace() const { return {}; }
    void prepare(double t, Workspace& w) const { w.context = at_time(t); }
    CAMFOLLOWER_FORCE_INLINE void force(const Workspace& w, const Vector& q, const Vector& v, Vector& f) const {
        w.last = nonlinear(w.context, q, v);
        f = w.last.force;
    }
    int max_rank() const { return 1; }
    void tangent(const Workspace& w, const Vector&, const Vector&, double cq, double cv, LowRank<Vector>& uv) const {
        const Nonlinear& n = w.last;
        if (n.contact.in_contact && (n.contact.stiffness != 0.0 || n.contact.damping != 0.0))
            uv.add(w.context.g, (cq * n.contact.stiffness + cv * n.contact.damping) * w.context.g +
                                    (cq * n.contact.damping) * w.context.g_dot);
    }
    void accepted(Workspace& w, const Vector&, const Vector&) const {
        const bool contact = w.last.contact.in_contact;
        if (contact == w.in_contact) return;
        if (!contact) w.loss_start = w.context.t;
        else w.contact_loss.emplace_back(w.loss_start, w.context.t);
        w.in_contact = contact;
    }
    // Contact-loss intervals up to time t_end (a loss still open at t_end ends there).
    static std::vector<std::pair<double, double>> contact_loss(const Workspace& w, double t_end) {
        std::vector<std::pair<double, double>> out = w.contact_loss;
        if (!w.in_contact) out.emplace_back(w.loss_start, t_end);
        return out;
    }
    std::vector<std::string> dof_names() const {
        std::vector<std::string> names;
        for (int k = 0; k < dofs; ++k) names.emplace_back(dof_name(k));
        return names;
    }
    std::vector<std::string> channel_names() const {
        return {"theta", "contact_force", "contact_stiffness", "pressure_angle", "penetration", "in_contact"};
    }
    // Switching function (solver/events.hpp): the cam-roller penetration (m), > 0 in contact.
    std::vector<std::string> event_names() const { return {"contact"}; }
    void event_values(const Workspace& w, const Vector&, const Vector&, double* g) const {
        g[0] = w.last.delta;  // force() at the same q, v computed it
    }
    void observe(const Workspace& w, const Vector& q, const Vector& v, double* out) const {
        const Nonlinear n = nonlinear(w.context, q, v);
        out[0] = w.context.theta;
        out[1] = n.contact.force;
        out[2] = n.contact.stiffness;
        out[3] = w.context.pressure_angle();
        out[4] = n.delta;
        out[5] = n.contact.in_contact ? 1.0 : 0.0;
    }
    const HertzContact& contact_law() const { return contact_; }
    double omega() const { return omega_; }
    double period() const { return two_pi / omega_; }
    double spring_preload() const { return preload_; }           // P, N
    const Vector& initial_state() const { return initial_state_; }  // static equilibrium at t = 0

    static const char* dof_name(int k) {
        static const char* names[dofs] = {"y1", "y2", "y3", "y4", "x1", "x2", "x3"};
        return names[k];
    }

    TimeContext at_time(double t) const {
        TimeContext c;
        c.t = t;
        c.theta = omega_ * t;
        const FollowerMotion m = cam_.program().evaluate(c.theta);
        // Effective offset: nominal + eccentricity's horizontal component + backlash side.
        double offset = parameters_.geometry.offset, offset_rate = 0.0, de_c = 0.0, de_c_rate = 0.0;
        c.side = 0.0;
        double side_rate = 0.0;
        if (defects_.eccentricity != 0.0) {
            const double phase = c.theta + defects_.eccentricity_phase;
            const double s = std::sin(phase), co = std::cos(phase);
            de_c = defects_.eccentricity * s;
            de_c_rate = defects_.eccentricity * co * omega_;
            // The cam centre moves by +eccentricity cos(phase) towards the follower axis (x):
            // the axis is then that much closer to it.
            offset -= defects_.eccentricity * co;
            offset_rate += defects_.eccentricity * s * omega_;
        }
        if (defects_.backlash != 0.0) {
            const BacklashSide::Value b = backlash_side_.at(c.theta);
            c.side = b.side;
            side_rate = b.dside * omega_;
            offset += defects_.backlash * b.side;
            offset_rate += defects_.backlash * side_rate;
        }
        c.offset = offset;
        const double s0 = offset == parameters_.geometry.offset ? s0_ : cam_.pitch_base(offset);
        c.kinematics = DiskCam::kinematics_from(m, s0, offset);
        const double ca = c.kinematics.cos_alpha, sa = c.kinematics.sin_alpha;
        // alpha = atan((R' - e) / R): d alpha/dt = omega d alpha/d theta + (d alpha/d e) de/dt,
        // d alpha/d e = (-R + (R' - e) e / s0) / (R^2 + (R' - e)^2).
        const double R = c.kinematics.R, p = c.kinematics.dR - offset;
        const double dalpha_de = (-R + p * offset / s0) / (R * R + p * p);
        const double alpha_rate = omega_ * c.kinematics.dalpha + dalpha_de * offset_rate;
        c.g.setZero();
        c.g[y1] = ca, c.g[y2] = -ca, c.g[x1] = -sa, c.g[x2] = sa;
        c.g_dot.setZero();
        c.g_dot[y1] = -sa * alpha_rate, c.g_dot[y2] = sa * alpha_rate;
        c.g_dot[x1] = -ca * alpha_rate, c.g_dot[x2] = ca * alpha_rate;
        c.delta0 = m.h * ca + de_c;
        c.delta0_dot = omega_ * m.dh * ca - m.h * sa * alpha_rate + de_c_rate;
        c.external = gravity_force_;
        c.external[y4] -= preload_;
        c.external[x3] += parameters_.guide_stiffness * defects_.backlash * c.side;
        return c;
    }

    CAMFOLLOWER_FORCE_INLINE Nonlinear nonlinear(const TimeContext& c, const Vector& q, const Vector& v) const {
        Nonlinear n;
        n.delta = c.g.dot(q) + c.delta0;
        n.delta_dot = c.g.dot(v) + c.g_dot.dot(q) + c.delta0_dot;
        n.contact = contact_(n.delta, n.delta_dot);
        n.force = n.contact.force * c.g - c.external;
        return n;
    }

    // Newton tangent of the nonlinear force when v depends on q as dv/dq = velocity_factor I:
    // d force / dq = g w^T (rank one), returned as w.
    Vector tangent_row(const TimeContext& c, const Nonlinear& n, double velocity_factor) const {
        return (n.contact.stiffness + n.contact.damping * velocity_factor) * c.g + n.contact.damping * c.g_dot;
    }

    // Quasi-static equilibrium at cam angle theta (t = theta / omega, zero velocity):
    // K q + F_c(delta) g = external. Newton from the contact-free deflection.
    Vector static_equilibrium(double theta) const {
        const TimeContext c = at_time(theta / omega_);
        Vector q = Eigen::PartialPivLU<Matrix>(K_).solve(c.external);
        const double scale = c.external.cwiseAbs().maxCoeff() + 1.0;
        const double norm_K = K_.cwiseAbs().rowwise().sum().maxCoeff();
        for (int it = 0; it < 100; ++it) {
            const ContactResponse f = contact_(c.g.dot(q) + c.delta0, 0.0);  // static: no rate term
            const Vector r = K_ * q + f.force * c.g - c.external;
            // 1e-12 of the load, or the rounding floor of K q when the lift makes q large.
            const double tolerance =
                std::max(1e-12 * scale, 64.0 * std::numeric_limits<double>::epsilon() * norm_K * q.cwiseAbs().maxCoeff());
            const Vector dq = dq_solve(f, c, r);
            q -= dq;
            // A very stiff contact (1e13 N/m) turns the rounding of the gap into newtons above the
            // load's 1e-12: a step at the rounding level of the position is as converged as it gets.
            const bool step_at_rounding = dq.cwiseAbs().maxCoeff() <= static_step_floor * (q.cwiseAbs().maxCoeff() + 1e-3);
            if (f.in_contact && (r.cwiseAbs().maxCoeff() <= tolerance || step_at_rounding)) return q;
        }
        throw ConvergenceError(detail::concat("static equilibrium at theta = ", radians_to_degrees(theta),
                                              " deg did not converge in 100 Newton iterations"));
    }

    // Newton step of the static solve with the contact's tangent.
    Vector dq_solve(const ContactResponse& f, const TimeContext& c, const Vector& r) const {
        return Eigen::PartialPivLU<Matrix>(K_ + f.stiffness * c.g * c.g.transpose()).solve(r);
    }
    static constexpr double static_step_floor = 1e-14;  // relative to |q| + 1 mm

    // Contact tangent stiffness (dF/d delta) at a state, for modal analysis.
    double contact_stiffness_at(double theta, const Vector& q) const {
        const TimeContext c = at_time(theta / omega_);
        return contact_(c.g.dot(q) + c.delta0, 0.0).stiffness;
    }

private:
    template <class T>
    static const T& validated(const T& value) {
        value.validate();
        return value;
    }

    // P such that the return-spring force at the theta = 0 static equilibrium (without defects)
    // is exactly K_rs delta_rs: a root of f(P) = P + K_rs y4(P) - K_rs delta_rs, by secant steps
    // (f is affine in P for the linear contact law, nearly so otherwise).
    void calibrate_preload() {
        const double target = parameters_.spring_stiffness * parameters_.spring_preload_deflection;
        const Defects saved = defects_;
        defects_ = Defects{};
        // The residual's rounding scales with its terms, which exceed the target when a soft contact
        // (10 N/m^n) deflects far: the tolerance follows the terms, not the target alone.
        double terms = target;
        auto residual = [&](double P) {
            preload_ = P;
            const double spring = parameters_.spring_stiffness * static_equilibrium(0.0)[y4];
            terms = std::abs(P) + std::abs(spring) + target;
            return P + spring - target;
        };
        const detail::SecantRoot root = detail::secant_root(residual, target, 1e-12 * target);
        const double f1 = root.residual;
        defects_ = saved;
        preload_ = root.x;
        if (!(std::abs(f1) <= 1e-9 * terms))
            throw ConvergenceError(detail::concat("spring preload calibration did not converge: spring force ",
                                                  target + f1, " N against K_rs delta_rs = ", target, " N"));
    }

    CamFollowerParameters parameters_;
    Defects defects_;
    DiskCam cam_;
    BacklashSide backlash_side_;
    LumpedNetwork<dofs> network_;
    Matrix M_, C_, K_;
    HertzContact contact_;
    double omega_ = 0.0, s0_ = 0.0, preload_ = 0.0;
    Vector gravity_force_ = Vector::Zero();
    Vector initial_state_ = Vector::Zero();
};

}  // namespace camfollower
