// SPDX-License-Identifier: BSD-3-Clause
// Radau IIA of order 5 (three stages, implicit, L-stable) with adaptive steps and dense output, for
// models that are stiff at the accuracy wanted: very stiff contacts and clearances, where the explicit
// methods' steps are bounded by stability (Hairer & Wanner, Solving ODE II, IV.8, and their code
// RADAU5). The system of core/system.hpp is integrated as y = (q, v), y' = (v, a(t, q, v)) with
// M a = -(C v + K q + f(t, q, v) - p(t)).
//
// Stage equations Z = h (A x I) F(y0 + Z), solved by simplified Newton with the Jacobian J at the
// step's start. Through the eigen-decomposition A^-1 = V diag(mu) V^-1 (one real eigenvalue, one
// complex pair) the 3n x 3n Newton system splits into (mu/h - J) x = r for the real mu and one of the
// complex pair; with J = [[0, I], [-M^-1 K_t, -M^-1 C_t]] (K_t, C_t: stiffness and damping with the
// contacts' tangent) each is one n x n system in the displacements:
//   (lambda^2 M + lambda C_t + K_t) x_q = M r_v + (lambda M + C_t) r_q,   x_v = lambda x_q - r_q.
// The tableau, its eigen-decomposition, the embedded error estimate and the collocation polynomial
// are computed from the closed-form coefficients (radau5::tableau), not copied digits.
//
// Error control as the explicit methods' (solver/error_scales.hpp): the mixed displacement/velocity
// norm and the force-weighted norm |K_t e_q + C_t e_v|_inf / (tol force_scale), both <= 1 (the latter
// floored at the rounding of the state through K_t and C_t), on Hairer's embedded third-order estimate e = (mu_real/h -
// J)^-1 (f(y0) + sum_i e_i Z_i / h). Steps by Gustafsson's predictive controller (exponent 1/4), as RADAU5.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/core/system.hpp"
#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/error_scales.hpp"
#include "camfollower/solver/events.hpp"
#include "camfollower/solver/first_order.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

namespace radau5 {

// The three-stage Radau IIA method and what the stepper derives from it.
struct Tableau {
    Eigen::Matrix3d A;
    Eigen::Vector3d c;
    double mu_real = 0.0;          // the real eigenvalue of A^-1
    std::complex<double> mu_pair;  // one of its complex pair
    // A^-1 = V diag(mu_real, mu_pair, conj) V^-1, V = [v_real, v_pair, conj(v_pair)]: the transformed
    // stages are w_real = w_row_real . Z (real), w_pair = w_row_pair . Z, and Z_i = v_real_i w_real +
    // 2 Re(v_pair_i w_pair).
    Eigen::Vector3d v_real;
    Eigen::Vector3cd v_pair;
    Eigen::RowVector3d w_row_real;
    Eigen::RowVector3cd w_row_pair;
    // Embedded estimate: e = (mu_real/h - J)^-1 (f(y0) + sum_i e_i Z_i / h).
    Eigen::RowVector3d e;
    // Collocation polynomial: y(t0 + x h) = y0 + sum_k x^(k+1) Q_k, Q = dense Z.
    Eigen::Matrix3d dense;
};

// A template so that only a unit instantiating the stepper instantiates its eigen solver.
template <class Real = double>
Tableau tableau() {
    const double s6 = std::sqrt(6.0);
    Tableau t;
    t.A << (88 - 7 * s6) / 360, (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225,  //
        (296 + 169 * s6) / 1800, (88 + 7 * s6) / 360, (-2 - 3 * s6) / 225,     //
        (16 - s6) / 36, (16 + s6) / 36, 1.0 / 9.0;
    t.c << (4 - s6) / 10, (4 + s6) / 10, 1.0;
    const Eigen::Matrix3d A_inv = t.A.inverse();
    const Eigen::EigenSolver<Eigen::Matrix3d> eig(A_inv);
    int real = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(eig.eigenvalues()[k].imag()) < std::abs(eig.eigenvalues()[real].imag())) real = k;
    const int pair = real == 0 ? 1 : 0;
    t.mu_real = eig.eigenvalues()[real].real();
    t.mu_pair = eig.eigenvalues()[pair];
    const Eigen::Vector3cd vr = eig.eigenvectors().col(real);
    int big = 0;  // a real eigenvector, whatever phase the solver gave it
    for (int k = 1; k < 3; ++k)
        if (std::abs(vr[k]) > std::abs(vr[big])) big = k;
    t.v_real = (vr / vr[big]).real();
    t.v_pair = eig.eigenvectors().col(pair);
    Eigen::Matrix3cd V;
    V.col(0) = t.v_real.cast<std::complex<double>>();
    V.col(1) = t.v_pair;
    V.col(2) = t.v_pair.conjugate();
    const Eigen::Matrix3cd W = V.inverse();
    t.w_row_real = W.row(0).real();
    t.w_row_pair = W.row(1);
    // The embedded third-order solution y0 + h (gamma0 f(y0) + sum b^_i f(Y_i)), gamma0 = 1/mu_real,
    // whose weights satisfy the quadrature conditions to order 3; e = mu_real (b^ - b) A^-1.
    const double gamma0 = 1.0 / t.mu_real;
    Eigen::Matrix3d Vc;
    Vc.row(0).setOnes();
    Vc.row(1) = t.c.transpose();
    Vc.row(2) = t.c.cwiseProduct(t.c).transpose();
    const Eigen::Vector3d b_hat = Vc.lu().solve(Eigen::Vector3d(1.0 - gamma0, 0.5, 1.0 / 3.0));
    t.e = t.mu_real * (b_hat.transpose() - t.A.row(2)) * A_inv;
    // Q_k from sum_k c_i^(k+1) Q_k = Z_i.
    Eigen::Matrix3d C;
    for (int i = 0; i < 3; ++i) C(i, 0) = t.c[i], C(i, 1) = t.c[i] * t.c[i], C(i, 2) = t.c[i] * t.c[i] * t.c[i];
    t.dense = C.inverse();
    return t;
}

}  // namespace radau5

template <class System>
class Radau : public FirstOrderStepper<Radau<System>, System> {
    using Base = FirstOrderStepper<Radau<System>, System>;
    friend Base;

public:
    using typename Base::Matrix;
    using typename Base::StateType;
    using typename Base::Vector;
    using Complex = std::complex<double>;
    using ComplexVector = Eigen::Matrix<Complex, Vector::RowsAtCompileTime, 1, 0, Vector::MaxRowsAtCompileTime, 1>;
    using ComplexMatrix = Eigen::Matrix<Complex, Matrix::RowsAtCompileTime, Matrix::ColsAtCompileTime, 0,
                                        Matrix::MaxRowsAtCompileTime, Matrix::MaxColsAtCompileTime>;
    static constexpr int max_newton_iterations = 7;  // RADAU5's default

    Radau(const System& system, const SolverSettings& settings)
        : Base(system, settings, Method::radau, "Radau"), tab_(radau5::tableau<>()), lu_real_(n_), lu_pair_(n_) {
        M_complex_ = system.mass().template cast<Complex>();
        for (Vector* x : {&a_, &qs_, &vs_, &as_, &q_old_, &v_old_, &eq_, &ev_, &tq_, &tv_, &dq_, &dv_, &w_real_q_,
                          &w_real_v_, &rq_, &rv_, &sum_})
            x->resize(n_);
        for (ComplexVector* x : {&w_pair_q_, &w_pair_v_, &rcq_, &rcv_, &xcq_, &xcv_, &tc_, &csum_}) x->resize(n_);
        for (auto* set : {&zq_, &zv_, &fq_, &fv_, &Qq_, &Qv_, &Pq_, &Pv_})
            for (Vector& x : *set) x.resize(n_);
        Kt_.resize(n_, n_), Ct_.resize(n_, n_), G_real_.resize(n_, n_), G_pair_.resize(n_, n_),
            Ct_complex_.resize(n_, n_);
    }
    Radau(System&&, const SolverSettings&) = delete;

private:
    using Base::acceleration, Base::reaches;
    using Base::system_, Base::s_, Base::adaptive_, Base::tolerance_, Base::n_, Base::M_inv_, Base::force_scale_,
        Base::t_, Base::t_start_, Base::fixed_steps_, Base::ws_, Base::scales_, Base::q_, Base::v_, Base::f_,
        Base::rhs_, Base::uvq_, Base::uvv_, Base::events_;

    // FirstOrderStepper's hooks: the start after the shared one, a step, the dense output.
    void restart(const StateType& s) {
        a_ = s.a;
        h_ = initial_step();
        t_old_ = t_, h_last_ = 0.0, h_old_ = 0.0, err_old_ = 0.0;
        faccon_ = 1.0;
        has_polynomial_ = false, rejected_last_ = false, event_retake_ = false, first_step_ = true;
    }
    void advance(double /*target*/, SolverStatistics& stats) { take_step(stats); }
    void dense_output(double t, Vector& q, Vector& v) const {
        polynomial(Qq_, Qv_, t, t_old_, h_last_, q_old_, v_old_, q, v);
    }

    // y' at (t, q, v) into (kq, kv) = (v, a); the workspace prepared at t with the force there.
    void derivative(double t, const Vector& q, const Vector& v, Vector& kq, Vector& kv, SolverStatistics& stats) {
        prepare(system_, t, ws_);
        nonlinear_force(system_, ws_, q, v, f_);
        kq = v;
        acceleration(q, v, f_, kv);
        ++stats.evaluations;
    }

    // The scaled error of a displacement/velocity pair (eq, ev), in units of the tolerance: the larger
    // of the mixed norm and the force-weighted norm (the explicit methods' test).
    double error_norm(const Vector& eq, const Vector& ev, const Vector& q1, const Vector& v1) {
        const double tol = tolerance_;
        rhs_.noalias() = Kt_ * eq;
        rhs_.noalias() += Ct_ * ev;
        return std::max(scales_.mixed(tol, eq, ev, q_, v_, q1, v1),
                        rhs_.cwiseAbs().maxCoeff() / std::max(tol * force_scale_, force_floor_));
    }

    // A starting step from the rates of change of y and y' (1/s): a fraction tol^(1/4) of the
    // fastest, at most the output interval; the controller (and the first step's refined estimate)
    // corrects it within a few steps.
    double initial_step() {
        SolverStatistics scratch;
        const double q_ref = scales_.q_ref, v_ref = scales_.v_ref;
        const double d1 =
            std::max(v_.cwiseAbs().maxCoeff() / (q_ref + 1e-12), a_.cwiseAbs().maxCoeff() / (v_ref + 1e-12));
        const double h0 = std::min(s_.time_step, 1e-6);
        qs_ = q_ + h0 * v_;
        vs_ = v_ + h0 * a_;
        derivative(t_ + h0, qs_, vs_, dq_, dv_, scratch);
        const double d2 = std::max((dq_ - v_).cwiseAbs().maxCoeff() / (q_ref + 1e-12),
                                   (dv_ - a_).cwiseAbs().maxCoeff() / (v_ref + 1e-12)) /
                          h0;
        const double rate = std::max({d1, std::sqrt(d2), scales_.omega_ref});
        derivative(t_, q_, v_, dq_, a_, scratch);  // the workspace back at the start, its force there
        return std::min(s_.time_step, 0.1 * std::pow(tolerance_, 0.25) / rate);
    }

    // K_t, C_t at the step's start (the workspace holds the force there).
    void jacobian() {
        tangent(system_, ws_, q_, v_, 1.0, 0.0, uvq_);
        tangent(system_, ws_, q_, v_, 0.0, 1.0, uvv_);
        Kt_ = system_.stiffness();
        Ct_ = system_.damping();
        // Column by column: an outer product would be a temporary for dynamic sizes.
        for (int r = 0; r < uvq_.rank; ++r)
            for (int j = 0; j < n_; ++j) Kt_.col(j) += uvq_.V(j, r) * uvq_.U.col(r);
        for (int r = 0; r < uvv_.rank; ++r)
            for (int j = 0; j < n_; ++j) Ct_.col(j) += uvv_.V(j, r) * uvv_.U.col(r);
        Ct_complex_ = Ct_.template cast<Complex>();
        // What rounding the state leaves in the forces, 16 eps max_i sum_j |K_t,ij q_j| + |C_t,ij v_j|:
        // a stiff spring turns the last bit of q into newtons, and no step gets the force error below it.
        double floor = 0.0;
        for (int i = 0; i < n_; ++i) {
            double row = 0.0;
            for (int j = 0; j < n_; ++j) row += std::abs(Kt_(i, j) * q_[j]) + std::abs(Ct_(i, j) * v_[j]);
            floor = std::max(floor, row);
        }
        force_floor_ = 16.0 * std::numeric_limits<double>::epsilon() * floor;
    }
    // (lambda^2 M + lambda C_t + K_t) for lambda = mu / h, real and complex, factored.
    void factor(double h) {
        const Matrix& M = system_.mass();
        const double lr = tab_.mu_real / h;
        const Complex lc = tab_.mu_pair / h;
        G_real_ = (lr * lr) * M + lr * Ct_ + Kt_;
        G_pair_ = (lc * lc) * M_complex_ + lc * Ct_complex_ + Kt_.template cast<Complex>();
        lu_real_.compute(G_real_);
        lu_pair_.compute(G_pair_);
    }
    // x = (lambda - J)^-1 r, real lambda = mu_real / h.
    void solve_real(double h, const Vector& r_q, const Vector& r_v, Vector& x_q, Vector& x_v) {
        const double lr = tab_.mu_real / h;
        sum_ = r_v + lr * r_q;  // a product's operand evaluated here, not into a temporary
        rhs_.noalias() = system_.mass() * sum_;
        rhs_.noalias() += Ct_ * r_q;
        x_q = lu_real_.solve(rhs_);
        x_v = lr * x_q - r_q;
    }
    void solve_pair(double h, const ComplexVector& r_q, const ComplexVector& r_v, ComplexVector& x_q,
                    ComplexVector& x_v) {
        const Complex lc = tab_.mu_pair / h;
        csum_ = r_v + lc * r_q;
        tc_.noalias() = M_complex_ * csum_;
        tc_.noalias() += Ct_complex_ * r_q;
        x_q = lu_pair_.solve(tc_);
        x_v = lc * x_q - r_q;
    }

    // Simplified Newton on the stage equations of the step [t_, t_ + h] from the guess in zq_, zv_;
    // false when it diverges or is too slow (the step is then retried at half the size).
    bool newton(double h, SolverStatistics& stats, int& iterations) {
        const double kappa =
            std::max(10.0 * std::numeric_limits<double>::epsilon() / tolerance_, std::min(0.03, std::sqrt(tolerance_)));
        w_real_q_.setZero(), w_real_v_.setZero(), w_pair_q_.setZero(), w_pair_v_.setZero();
        for (int i = 0; i < 3; ++i) {
            w_real_q_ += tab_.w_row_real[i] * zq_[i], w_real_v_ += tab_.w_row_real[i] * zv_[i];
            w_pair_q_ += tab_.w_row_pair[i] * zq_[i].template cast<Complex>();
            w_pair_v_ += tab_.w_row_pair[i] * zv_[i].template cast<Complex>();
        }
        faccon_ = std::pow(std::max(faccon_, std::numeric_limits<double>::epsilon()), 0.8);
        double norm_old = 0.0;
        for (iterations = 0; iterations < max_newton_iterations;) {
            for (int i = 0; i < 3; ++i) {
                qs_ = q_ + zq_[i];
                vs_ = v_ + zv_[i];
                derivative(t_ + tab_.c[i] * h, qs_, vs_, fq_[i], fv_[i], stats);
            }
            // r = V^-1 F - (mu / h) w, for the real eigenvalue and the pair.
            rq_ = -(tab_.mu_real / h) * w_real_q_, rv_ = -(tab_.mu_real / h) * w_real_v_;
            rcq_ = -(tab_.mu_pair / h) * w_pair_q_, rcv_ = -(tab_.mu_pair / h) * w_pair_v_;
            for (int i = 0; i < 3; ++i) {
                rq_ += tab_.w_row_real[i] * fq_[i], rv_ += tab_.w_row_real[i] * fv_[i];
                rcq_ += tab_.w_row_pair[i] * fq_[i].template cast<Complex>();
                rcv_ += tab_.w_row_pair[i] * fv_[i].template cast<Complex>();
            }
            if (!(rq_.allFinite() && rv_.allFinite())) return false;
            solve_real(h, rq_, rv_, dq_, dv_);
            solve_pair(h, rcq_, rcv_, xcq_, xcv_);
            ++iterations;
            w_real_q_ += dq_, w_real_v_ += dv_, w_pair_q_ += xcq_, w_pair_v_ += xcv_;
            // The stages' increments, measured like the error.
            double norm = 0.0;
            for (int i = 0; i < 3; ++i) {
                tq_ = tab_.v_real[i] * dq_ + 2.0 * (tab_.v_pair[i] * xcq_).real();
                tv_ = tab_.v_real[i] * dv_ + 2.0 * (tab_.v_pair[i] * xcv_).real();
                zq_[i] += tq_, zv_[i] += tv_;
                norm = std::max(norm, error_norm(tq_, tv_, q_, v_));
            }
            if (!std::isfinite(norm)) return false;
            if (iterations > 1) {
                const double theta = norm / norm_old;
                if (theta >= 0.99) return false;
                // Too slow to reach kappa within the iterations left.
                if (std::pow(theta, max_newton_iterations - iterations) / (1.0 - theta) * norm > kappa) return false;
                faccon_ = theta / (1.0 - theta);
            }
            if (norm == 0.0 || faccon_ * norm <= kappa) return true;
            norm_old = norm;
        }
        return false;
    }

    // Hairer's estimate e = (mu_real/h - J)^-1 (f(y0) + sum_i e_i Z_i / h), in units of the tolerance;
    // on a first step or after a rejection a large estimate is refined once through f(y0 + e).
    double error_estimate(double h, SolverStatistics& stats) {
        tq_.setZero(), tv_.setZero();
        for (int i = 0; i < 3; ++i) tq_ += (tab_.e[i] / h) * zq_[i], tv_ += (tab_.e[i] / h) * zv_[i];
        dq_ = v_ + tq_, dv_ = a_ + tv_;
        solve_real(h, dq_, dv_, eq_, ev_);
        double err = error_norm(eq_, ev_, qs_, vs_);
        if (err > 1.0 && (first_step_ || rejected_last_)) {
            dq_ = q_ + eq_;
            dv_ = v_ + ev_;
            derivative(t_, dq_, dv_, rq_, rv_, stats);
            rq_ += tq_, rv_ += tv_;
            solve_real(h, rq_, rv_, eq_, ev_);
            err = error_norm(eq_, ev_, qs_, vs_);
        }
        return std::isfinite(err) ? err : 1e10;
    }

    // Gustafsson's predictive controller (RADAU5): the factor the step is multiplied by.
    double step_factor(double h, double err, int iterations) const {
        double multiplier = 1.0;
        if (h_old_ > 0.0 && err_old_ > 0.0 && err > 0.0) multiplier = h / h_old_ * std::pow(err_old_ / err, 0.25);
        const double factor = std::min(1.0, multiplier) * std::pow(std::max(err, 1e-10), -0.25);
        const double safety = 0.9 * (2 * max_newton_iterations + 1) / double(2 * max_newton_iterations + iterations);
        return safety * factor;
    }

    void take_step(SolverStatistics& stats) {
        const double min_step = 1e-14 * std::max(1.0, std::abs(t_));
        jacobian();
        double factored = -1.0;
        for (;;) {
            double h = h_;
            if (s_.max_step > 0.0) h = std::min(h, s_.max_step);
            if (!adaptive_) h = s_.max_step;  // fixed steps (FirstOrderStepper requires max_step without a tolerance)
            if (!(h >= min_step))
                throw ConvergenceError(detail::concat(
                    "Radau IIA: the step fell to ", h, " s at t = ", t_, " s without meeting tolerance = ", tolerance_,
                    " (the response is not smooth there, or the tolerance is below rounding)"));
            if (h != factored) factor(h), factored = h;
            // Start from the last step's collocation polynomial, extrapolated.
            for (int i = 0; i < 3; ++i) {
                if (has_polynomial_) {
                    polynomial(Qq_, Qv_, t_ + tab_.c[i] * h, t_old_, h_last_, q_old_, v_old_, zq_[i], zv_[i]);
                    zq_[i] -= q_, zv_[i] -= v_;
                } else {
                    zq_[i].setZero(), zv_[i].setZero();
                }
            }
            int iterations = 0;
            const bool converged = newton(h, stats, iterations);
            stats.newton_iterations += std::uint64_t(iterations);
            stats.max_iterations_in_a_step = std::max(stats.max_iterations_in_a_step, iterations);
            if (!converged) {
                if (!adaptive_)
                    throw ConvergenceError(detail::concat("Radau IIA: Newton did not converge at t = ", t_,
                                                          " s with the fixed step ", h, " s"));
                h_ = 0.5 * h;
                rejected_last_ = true, event_retake_ = false, faccon_ = 1.0;
                ++stats.rejected_steps;
                continue;
            }
            qs_ = q_ + zq_[2];
            vs_ = v_ + zv_[2];
            double err = error_estimate(h, stats);
            if (!adaptive_) err = 0.5;
            if (err > 1.0) {
                h_ = h * std::max(0.2, step_factor(h, err, iterations));
                rejected_last_ = true, event_retake_ = false;
                ++stats.rejected_steps;
                continue;
            }
            double h_new = h * std::min(10.0, step_factor(h, err, iterations));
            derivative(t_ + h, qs_, vs_, dq_, as_, stats);  // the workspace at the new state, its force there
            if constexpr (has_events_v<System>) {
                if (end_at_crossing(h, h_new)) continue;
            }
            if (event_retake_) h_new = std::max(h_new, h_before_event_);
            event_retake_ = false;
            accept(h, err);
            h_ = rejected_last_ ? std::min(h_new, h) : h_new;
            rejected_last_ = false;
            ++stats.steps;
            return;
        }
    }

    // As the explicit methods: a sign change inside the step retakes it to end just past the earliest
    // crossing (located on the collocation polynomial); the retake's crossings are recorded.
    bool end_at_crossing(double h, double h_new) {
        if (!events_.changed(ws_, qs_, vs_)) return false;
        trial_polynomial();
        auto path = [&](double t, Vector& q, Vector& v) { polynomial(Pq_, Pv_, t, t_, h, q_, v_, q, v); };
        const Crossing first = events_.earliest(t_, t_ + h, path);
        if (adaptive_ && !event_retake_ && first.beyond < t_ + h && first.beyond - t_ > 1e-6 * h) {
            event_retake_ = true;
            h_before_event_ = h_new;
            h_ = first.beyond - t_;
            return true;
        }
        events_.record(first, ws_);
        while (const Crossing c = events_.earliest(t_, t_ + h, path)) events_.record(c, ws_);
        return false;
    }

    void accept(double h, double err) {
        double t_new = t_start_ + double(fixed_steps_ + 1) * h;
        if (adaptive_) t_new = t_ + h;
        if (!adaptive_) ++fixed_steps_;
        trial_polynomial();
        std::swap(Qq_, Pq_), std::swap(Qv_, Pv_);
        q_old_ = q_, v_old_ = v_;
        t_old_ = t_, h_old_ = h, h_last_ = h, t_ = t_new;
        err_old_ = err;
        has_polynomial_ = true, first_step_ = false;
        q_ = qs_, v_ = vs_, a_ = as_;
        scales_.update(q_, v_);
        accepted(system_, ws_, q_, v_);
    }

    // The collocation polynomial of the stages just solved, into Pq_, Pv_.
    void trial_polynomial() {
        for (int k = 0; k < 3; ++k) {
            Pq_[k].setZero(), Pv_[k].setZero();
            for (int i = 0; i < 3; ++i) Pq_[k] += tab_.dense(k, i) * zq_[i], Pv_[k] += tab_.dense(k, i) * zv_[i];
        }
    }
    // A collocation polynomial (Qq, Qv) of the step [t0, t0 + h] from (q0, v0), at t.
    static void polynomial(const std::array<Vector, 3>& Qq, const std::array<Vector, 3>& Qv, double t, double t0,
                           double h, const Vector& q0, const Vector& v0, Vector& q, Vector& v) {
        const double x = h > 0.0 ? (t - t0) / h : 1.0;
        q = q0 + x * (Qq[0] + x * (Qq[1] + x * Qq[2]));
        v = v0 + x * (Qv[0] + x * (Qv[1] + x * Qv[2]));
    }

    radau5::Tableau tab_;
    Matrix Kt_, Ct_, G_real_;
    ComplexMatrix G_pair_, M_complex_, Ct_complex_;  // M and C_t as complex, for the complex pair's solve
    double force_floor_ = 0.0;
    double t_old_ = 0.0, h_ = 0.0, h_last_ = 0.0, h_old_ = 0.0, err_old_ = 0.0, faccon_ = 1.0;
    double h_before_event_ = 0.0;
    bool has_polynomial_ = false, rejected_last_ = false, event_retake_ = false, first_step_ = true;
    // Scratch, sized once: nothing is allocated inside the time loop.
    Vector a_, qs_, vs_, as_, q_old_, v_old_, eq_, ev_, tq_, tv_, dq_, dv_, w_real_q_, w_real_v_, rq_, rv_, sum_;
    ComplexVector w_pair_q_, w_pair_v_, rcq_, rcv_, xcq_, xcv_, tc_, csum_;
    std::array<Vector, 3> zq_, zv_, fq_, fv_, Qq_, Qv_, Pq_, Pv_;  // Q: the last accepted step's polynomial
    Eigen::PartialPivLU<Matrix> lu_real_;
    Eigen::PartialPivLU<ComplexMatrix> lu_pair_;
};

}  // namespace camfollower
