// SPDX-License-Identifier: BSD-3-Clause
// A minimal, tight Newmark/Newton stepper: what a skilled user would write by hand for a small model,
// as the yardstick for camfollower::Newmark's per-step overhead (bench only, not part of the library).
//
// The same scheme and the same Newton acceptance as camfollower::Newmark (unknown: the new
// acceleration; accepted when the residual is below tolerance and either the increment is, or the
// next increment is bounded below it through 1 / lambda_min(A0)), on the same model evaluation
// (prepare, force, tangent of the system contract), so both produce the same states to the Newton
// tolerance. Left out: HHT-alpha, step halving, the residual's rounding floor, error messages, events,
// path memory (accepted()), a tangent of rank above one, sparse algebra.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/core/system.hpp"

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
          ws_(system.workspace()),
          uv_(system.size(), system.max_rank()) {
        const Matrix A0 =
            system.mass() / (beta * dt * dt) + gamma / (beta * dt) * system.damping() + system.stiffness();
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
        a_ = -system_.mass().partialPivLu().solve(system_.damping() * v + system_.stiffness() * q + f_);
    }

    // One step; false when Newton did not converge (no recovery: the caller gives up).
    bool step() {
        const double q_step = beta_ * dt_ * dt_, v_step = gamma_ * dt_;
        t_ += dt_;
        system_.prepare(t_, ws_);
        const Vector q_pred = q_ + dt_ * v_ + (dt_ * dt_ * (0.5 - beta_)) * a_;
        const Vector v_pred = v_ + (dt_ * (1.0 - gamma_)) * a_;
        const Vector b = system_.damping() * v_pred + system_.stiffness() * q_pred;
        for (int iteration = 0; iteration < 25; ++iteration) {
            q_ = q_pred + q_step * a_;
            v_ = v_pred + v_step * a_;
            system_.force(ws_, q_, v_, f_);
            const Vector r = Aa_ * a_ + b + f_;
            uv_.clear();
            system_.tangent(ws_, q_, v_, 1.0, gamma_ / (beta_ * dt_), uv_);
            const double tol = q_tol_ * (q_.cwiseAbs().maxCoeff() + 1e-9);
            const bool residual_ok = r.cwiseAbs().maxCoeff() <= r_tol_;
            // A contact tangent g k g^T is positive semi-definite: |A^-1 r| <= |r| / lambda_min(A0).
            if (iteration > 0 && residual_ok && r.norm() * inverse_bound_ <= tol) return true;
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
                return true;
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
    const System& system_;
    double dt_, beta_, gamma_;
    typename System::Workspace ws_;
    camfollower::LowRank<Vector> uv_;
    Matrix A0_inv_, Aa_;
    double inverse_bound_ = 0.0, r_tol_ = 0.0, q_tol_ = 0.0;
    double t_ = 0.0;
    Vector q_, v_, a_, f_;
};

}  // namespace bench
