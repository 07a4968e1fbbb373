// SPDX-License-Identifier: BSD-3-Clause
// A minimal, tight Newmark/Newton stepper: what a skilled user would write by hand for a small model,
// as the yardstick for camfollower::Newmark's per-step overhead (bench only, not part of the library).
//
// The same scheme and the same Newton acceptance as camfollower::Newmark (unknown: the new
// acceleration; accepted when the residual is below tolerance and either the increment is, or the
// next increment is bounded below it through 1 / lambda_min(A0)), on the same model evaluation
// (prepare, force, tangent of the system contract), so both produce the same states to the Newton
// tolerance. With gamma = 1/2 and beta < 1/4 the velocity is processed to fourth order as
// camfollower's is (NewmarkParameters::processed; equal steps only). Left out: HHT-alpha, step
// halving, the residual's rounding floor, error messages, events, path memory (accepted()), a tangent
// of rank above one, sparse algebra.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/core/system.hpp"
#include "camfollower/solver/settings.hpp"

namespace bench {

template <class System>
class TightNewmark {
public:
    using Vector = typename System::Vector;
    using Matrix = typename System::Matrix;

    TightNewmark(const System& system, double dt, double beta, double gamma = 0.5, double tolerance = 1e-10)
        : system_(system),
          dt_(dt),
          beta_(beta),
          gamma_(gamma),
          processed_(gamma == 0.5 && beta < 0.25),
          v_gamma_(processed_ ? camfollower::processed_damping_gamma : gamma),
          ws_(system.workspace()),
          uv_(system.size(), system.max_rank()) {
        const Matrix A0 =
            system.mass() / (beta * dt * dt) + v_gamma_ / (beta * dt) * system.damping() + system.stiffness();
        A0_inv_ = A0.partialPivLu().inverse();
        Aa_ = (beta * dt * dt) * A0;
        inverse_bound_ = 1.0 / Eigen::SelfAdjointEigenSolver<Matrix>(A0, Eigen::EigenvaluesOnly).eigenvalues()[0];
        Vector Kq = system.stiffness() * system.initial_displacement();
        r_tol_ = tolerance * std::max(1.0, Kq.cwiseAbs().maxCoeff());
        q_tol_ = tolerance;
    }

    void start(double t, const Vector& q, const Vector& v) {
        t_ = t, q_ = q, v_ = v;
        system_.prepare(t, ws_);
        system_.force(ws_, q, v, f_);
        a_ = acceleration(q, v);
        if (!processed_) return;
        const double d = 1e-3 * dt_;  // the jerk along the Taylor line, as camfollower starts it
        system_.prepare(t + d, ws_);
        const Vector ahead = acceleration(q + d * v, v + d * a_);
        system_.prepare(t - d, ws_);
        const Vector behind = acceleration(q - d * v, v - d * a_);
        system_.prepare(t, ws_);
        system_.force(ws_, q, v, f_);
        jerk_ = (ahead - behind) / (2.0 * d);
        first_ = true;
    }

    // One step; false when Newton did not converge (no recovery: the caller gives up).
    bool step() {
        const double q_step = beta_ * dt_ * dt_, w = dt_ * dt_ / 12.0;
        // The first step's jerk is the trapezoidal rule's, 2 (a1 - a0) / dt - a'0, as camfollower's.
        const double v_step = processed_ && first_ ? dt_ / 3.0 : v_gamma_ * dt_;
        t_ += dt_;
        system_.prepare(t_, ws_);
        Vector q_pred = q_ + dt_ * v_ + (dt_ * dt_ * (0.5 - beta_)) * a_;
        Vector v_pred = v_ + (dt_ * (1.0 - gamma_)) * a_;
        const Vector a_old = a_;
        if (processed_) {  // v = vN - dt^2 / 12 a', a' = (3 a1 - 4 a0 + a_prev) / 2 dt
            q_pred += (dt_ * w) * jerk_;
            v_pred += w * jerk_ + (2.0 * w / dt_) * a_;
            v_pred += first_ ? Vector(w * jerk_) : Vector(-(0.5 * w / dt_) * a_prev_);
        }
        const Vector b = system_.damping() * v_pred + system_.stiffness() * q_pred;
        for (int iteration = 0; iteration < 25; ++iteration) {
            q_ = q_pred + q_step * a_;
            v_ = v_pred + v_step * a_;
            system_.force(ws_, q_, v_, f_);
            Vector r = Aa_ * a_ + b + f_;
            if (v_step != v_gamma_ * dt_) r += (v_step - v_gamma_ * dt_) * (system_.damping() * a_);  // first step
            uv_.clear();
            system_.tangent(ws_, q_, v_, 1.0, v_step / q_step, uv_);
            const double tol = q_tol_ * (q_.cwiseAbs().maxCoeff() + 1e-9);
            const bool residual_ok = r.cwiseAbs().maxCoeff() <= r_tol_;
            // A contact tangent g k g^T is positive semi-definite: |A^-1 r| <= |r| / lambda_min(A0).
            if (iteration > 0 && residual_ok && r.norm() * inverse_bound_ <= tol) return advance(a_old);
            Vector dq = A0_inv_ * r;
            if (uv_.rank == 1) {
                const Vector z = A0_inv_ * uv_.U.col(0);
                dq -= z * (uv_.V.col(0).dot(dq) / (1.0 + uv_.V.col(0).dot(z)));
            }
            a_ -= dq / q_step;
            if (residual_ok && dq.cwiseAbs().maxCoeff() <= tol) {
                q_ = q_pred + q_step * a_;
                v_ = v_pred + v_step * a_;
                system_.force(ws_, q_, v_, f_);
                return advance(a_old);
            }
        }
        return false;
    }

    double time() const { return t_; }
    const Vector& q() const { return q_; }
    const Vector& v() const { return v_; }
    const Vector& a() const { return a_; }
    const Vector& f() const { return f_; }
    const typename System::Workspace& workspace() const { return ws_; }

private:
    Vector acceleration(const Vector& q, const Vector& v) {
        system_.force(ws_, q, v, f_);
        return -system_.mass().partialPivLu().solve(system_.damping() * v + system_.stiffness() * q + f_);
    }
    bool advance(const Vector& a_old) {
        if (processed_) {
            jerk_ = first_ ? Vector(2.0 * (a_ - a_old) / dt_ - jerk_)
                           : Vector((1.5 * a_ - 2.0 * a_old + 0.5 * a_prev_) / dt_);
            a_prev_ = a_old;
            first_ = false;
        }
        return true;
    }

    const System& system_;
    double dt_, beta_, gamma_;
    bool processed_, first_ = false;
    double v_gamma_;  // the velocity's coefficient of the new acceleration, per unit step
    typename System::Workspace ws_;
    camfollower::LowRank<Vector> uv_;
    Matrix A0_inv_, Aa_;
    double inverse_bound_ = 0.0, r_tol_ = 0.0, q_tol_ = 0.0;
    double t_ = 0.0;
    Vector q_, v_, a_, f_, jerk_, a_prev_;
};

}  // namespace bench
