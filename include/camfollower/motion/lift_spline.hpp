// SPDX-License-Identifier: BSD-3-Clause
// A lift table (theta, h) as a B-spline of odd degree: interpolating (smoothing = 0) or smoothing.
//
// Two shapes:
// - periodic(): the whole revolution. theta strictly increasing in [0, 2 pi), NOT closed: the point
//   one revolution after the first is implied (a closing point at theta[0] + 2 pi with h equal to h[0]
//   is accepted and dropped; one with a different h is refused). Knots at the table points, so the
//   interpolating spline is the classical periodic spline interpolant of odd degree (de Boor, "A
//   Practical Guide to Splines", 2001, ch. XIII) and C^(degree-1) everywhere, wrap included.
// - segment(): one segment of a program, theta absolute, spanning [theta.front(), theta.back()]. The
//   end values h.front(), h.back() and the end derivatives h', h'', ... (m/rad^k, up to degree - 1 at
//   each end; default zeros up to degree - 1, so the segment meets a dwell C^(degree-1)) are imposed
//   exactly, also when smoothing. Knots by de Boor's knot averaging over the data sites (end sites
//   counted once per imposed condition), which satisfies the Schoenberg-Whitney conditions.
//
// Smoothing (Reinsch 1967; de Boor ch. XIV): with lambda = options.smoothing >= 0 and m = (degree+1)/2
// the spline s minimizes
//     sum_i (s(theta_i) - h_i)^2  +  lambda * integral (d^m s / dtheta^m)^2 dtheta      (m^2)
// over the spline space (for the periodic shape this is exactly the periodic smoothing spline). lambda
// has units rad^degree (rad^(2m-1)). For N equally spaced points Delta = 2 pi / N apart, a harmonic of
// k waves per revolution keeps the fraction 1 / (1 + lambda * Delta * k^(2m)) of its amplitude: to
// halve harmonic k_c take lambda = 1 / (Delta * k_c^(2m)).
//
// Fitting solves a sparse (cyclic-)banded system with Eigen's SparseLU: O(N). The result is stored in
// piecewise-polynomial (Taylor) form; evaluation is a binary search and Horner, without allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "camfollower/detail/extremum.hpp"
#include "camfollower/detail/linear_solvers.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/bspline_basis.hpp"
#include "camfollower/motion/follower_motion.hpp"
#include "camfollower/motion/lift_peaks.hpp"

namespace camfollower {

struct SplineOptions {
    int degree = 5;          // odd: 1, 3, 5 (default, C4) or 7
    double smoothing = 0.0;  // lambda >= 0 (rad^degree); 0 interpolates the table
};

// How far a fit passes from its table points (m) and where the largest miss is (rad).
struct FitResidual {
    double max = 0.0;
    double rms = 0.0;
    double theta_of_max = 0.0;
};

class LiftSpline {
public:
    static constexpr double period = 6.283185307179586476925286766559;  // one revolution, rad

    static LiftSpline periodic(std::vector<double> theta, std::vector<double> h, const SplineOptions& options = {}) {
        check_options(options);
        check_table(theta, h);
        close_table(theta, h);
        const std::size_t n = theta.size();
        for (std::size_t i = 0; i < n; ++i)
            if (theta[i] < 0.0 || theta[i] >= period)
                detail::fail("theta[", i, "] = ", theta[i] * 180.0 / pi_,
                             " deg must be in [0, 360) deg: a periodic "
                             "table covers one revolution (the spline repeats it)");
        const std::size_t p = static_cast<std::size_t>(options.degree);
        if (n < p + 1)
            detail::fail("theta: a periodic spline of degree ", p, " needs at least ", p + 1,
                         " distinct points per revolution, got ", n);
        LiftSpline s(true, options, std::move(theta), std::move(h), {}, {});
        s.fit_periodic();
        return s;
    }

    static LiftSpline segment(std::vector<double> theta, std::vector<double> h, const SplineOptions& options = {},
                              std::vector<double> start_derivatives = {}, std::vector<double> end_derivatives = {}) {
        check_options(options);
        check_table(theta, h);
        if (theta.size() < 2) detail::fail("theta: a segment table needs at least 2 points, got ", theta.size());
        const std::size_t highest = static_cast<std::size_t>(options.degree - 1);
        for (auto* d : {&start_derivatives, &end_derivatives}) {
            const char* name = d == &start_derivatives ? "start_derivatives" : "end_derivatives";
            if (d->empty()) d->assign(highest, 0.0);
            if (d->size() > highest)
                detail::fail(name, " may hold h', h'', ... up to order degree - 1 = ", highest, ", got ", d->size(),
                             " values");
            for (std::size_t k = 0; k < d->size(); ++k)
                if (!std::isfinite((*d)[k]))
                    detail::fail(name, "[", k, "] (derivative of order ", k + 1, ", m/rad^", k + 1,
                                 ") must be finite, got ", (*d)[k]);
        }
        const std::size_t conditions = theta.size() + start_derivatives.size() + end_derivatives.size();
        if (conditions < highest + 2)
            detail::fail("theta: a segment spline of degree ", options.degree, " needs at least ", highest + 2,
                         " conditions (table points plus end derivatives), got ", conditions);
        LiftSpline s(false, options, std::move(theta), std::move(h), std::move(start_derivatives),
                     std::move(end_derivatives));
        s.fit_segment();
        return s;
    }

    bool is_periodic() const { return periodic_; }
    int degree() const { return degree_; }
    double smoothing() const { return smoothing_; }
    // The table as fitted (a periodic table's closing point dropped), rad and m.
    const std::vector<double>& theta() const { return theta_; }
    const std::vector<double>& h() const { return h_; }
    // Imposed end derivatives h', h'', ... (m/rad^k) of a segment spline; empty for a periodic one.
    const std::vector<double>& start_derivatives() const { return start_derivatives_; }
    const std::vector<double>& end_derivatives() const { return end_derivatives_; }
    // Boundaries of the polynomial pieces (rad, ascending; one revolution for a periodic spline).
    const std::vector<double>& breaks() const { return breaks_; }

    // Where its segment starts (rad): 0 for a periodic spline (its program spans [0, 2 pi)), else theta.front().
    double origin() const { return periodic_ ? 0.0 : theta_.front(); }
    double span() const { return periodic_ ? period : theta_.back() - theta_.front(); }
    // Lift gained over its segment (m): 0 for a periodic spline, h.back() - h.front() for a segment.
    double net_lift() const { return periodic_ ? 0.0 : h_.back() - h_.front(); }
    // Peaks of |h'|, |h''|, |h'''| over the spline (angles absolute, in [0, 2 pi) when periodic).
    const LiftPeaks& peaks() const { return peaks_; }
    // Lowest and highest lift over the span, relative to the segment start (m).
    std::pair<double, double> relative_range() const { return {range_.first - base_, range_.second - base_}; }

    std::string name() const {
        return detail::concat(periodic_ ? "periodic spline(degree=" : "spline(degree=", degree_,
                              ", points=", theta_.size(),
                              smoothing_ > 0.0 ? detail::concat(", smoothing=", smoothing_) : std::string(), ")");
    }

    // s and its derivatives at an absolute theta (rad). Periodic: any theta. Segment: theta within
    // [theta.front(), theta.back()] (an excursion of 1e-9 rad is clamped).
    FollowerMotion evaluate(double theta) const {
        double t = theta;
        if (periodic_) {
            t = std::fmod(theta - breaks_.front(), period);
            if (t < 0.0) t += period;
            t += breaks_.front();
        } else {
            if (!(theta >= breaks_.front() - 1e-9 && theta <= breaks_.back() + 1e-9))
                detail::fail("theta = ", theta, " rad is outside the spline's span [", breaks_.front(), ", ",
                             breaks_.back(), "] rad");
            t = std::fmin(std::fmax(theta, breaks_.front()), breaks_.back());
        }
        const auto it = std::upper_bound(breaks_.begin() + 1, breaks_.end() - 1, t);
        const std::size_t piece = static_cast<std::size_t>(it - breaks_.begin()) - 1;
        const double x = t - breaks_[piece];
        const double* a = taylor_.data() + piece * static_cast<std::size_t>(degree_ + 1);
        double v = a[degree_], d1 = 0.0, d2 = 0.0, d3 = 0.0;  // dk accumulates s^(k) / k!
        for (int r = degree_ - 1; r >= 0; --r) {
            d3 = d3 * x + d2;
            d2 = d2 * x + d1;
            d1 = d1 * x + v;
            v = v * x + a[r];
        }
        return {v, d1, 2.0 * d2, 6.0 * d3};
    }

    // Relative to its segment: s(origin + u) - s(origin), u in [0, span] (rad).
    FollowerMotion relative(double u) const {
        FollowerMotion m = evaluate(origin() + u);
        m.h -= base_;
        return m;
    }

    // Misses at the table points: zero to rounding for an interpolating spline.
    FitResidual residual() const {
        FitResidual r;
        double sum = 0.0;
        for (std::size_t i = 0; i < theta_.size(); ++i) {
            const double e = std::abs(evaluate(theta_[i]).h - h_[i]);
            sum += e * e;
            if (e > r.max) r.max = e, r.theta_of_max = theta_[i];
        }
        r.rms = std::sqrt(sum / static_cast<double>(theta_.size()));
        return r;
    }

private:
    static constexpr double pi_ = period / 2.0;
    using Triplets = std::vector<Eigen::Triplet<double>>;

    LiftSpline(bool periodic, const SplineOptions& options, std::vector<double> theta, std::vector<double> h,
               std::vector<double> start_derivatives, std::vector<double> end_derivatives)
        : periodic_(periodic),
          degree_(options.degree),
          smoothing_(options.smoothing),
          theta_(std::move(theta)),
          h_(std::move(h)),
          start_derivatives_(std::move(start_derivatives)),
          end_derivatives_(std::move(end_derivatives)) {}

    static void check_options(const SplineOptions& options) {
        if (options.degree < 1 || options.degree > detail::max_spline_degree || options.degree % 2 == 0)
            detail::fail("degree must be odd: 1, 3, 5 or 7, got ", options.degree);
        detail::require_non_negative(options.smoothing, "smoothing", "(rad^degree)");
    }

    static void check_table(const std::vector<double>& theta, const std::vector<double>& h) {
        if (theta.size() != h.size())
            detail::fail("theta and h must have the same length, got ", theta.size(), " and ", h.size());
        for (std::size_t i = 0; i < theta.size(); ++i) {
            if (!std::isfinite(theta[i])) detail::fail("theta[", i, "] must be finite (rad), got ", theta[i]);
            if (!std::isfinite(h[i])) detail::fail("h[", i, "] must be finite (m), got ", h[i]);
            if (i > 0 && !(theta[i] > theta[i - 1]))
                detail::fail("theta must be strictly increasing: theta[", i, "] = ", theta[i] * 180.0 / pi_,
                             " deg does not come after theta[", i - 1, "] = ", theta[i - 1] * 180.0 / pi_, " deg");
        }
    }

    // A periodic table repeating its first point one revolution later: drop the repeat if its h agrees.
    static void close_table(std::vector<double>& theta, std::vector<double>& h) {
        if (theta.size() < 2 || std::abs(theta.back() - (theta.front() + period)) > 1e-9) return;
        double scale = 0.0;
        for (double v : h) scale = std::max(scale, std::abs(v));
        if (std::abs(h.back() - h.front()) > 1e-12 + 1e-9 * scale)
            detail::fail("h: the table repeats its first point one revolution later (theta[", theta.size() - 1,
                         "] = theta[0] + 360 deg) with h = ", h.back(), " m, not h[0] = ", h.front(),
                         " m; a periodic table must not be closed (leave that point out)");
        theta.pop_back();
        h.pop_back();
    }

    static Eigen::VectorXd solve(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b) {
        Eigen::VectorXd x;
        if (!detail::sparse_lu_solve(a, b, x))
            detail::fail("theta: the spline system is singular for this table (points too close together?)");
        return x;
    }

    // Adds lambda * integral of (s^(m))^2 over the pieces [knots[k], knots[k+1]], k in [first, last),
    // exactly (4-point Gauss-Legendre: the integrand has degree <= 2 (p - m) <= 6).
    template <class Column>
    void add_penalty(Triplets& t, const std::vector<double>& knots, std::size_t first, std::size_t last,
                     const Column& column) const {
        const int p = degree_, m = (degree_ + 1) / 2;
        static constexpr double gx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                         0.8611363115940526};
        static constexpr double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                         0.3478548451374538};
        for (std::size_t k = first; k < last; ++k) {
            const double a = knots[k], b = knots[k + 1], half = 0.5 * (b - a);
            if (!(b > a)) continue;
            for (int g = 0; g < 4; ++g) {
                const detail::BasisDerivatives d = detail::basis_derivatives(knots, k, a + half * (1.0 + gx[g]), p, m);
                for (int i = 0; i <= p; ++i)
                    for (int j = 0; j <= p; ++j)
                        t.emplace_back(column(k, i), column(k, j), smoothing_ * gw[g] * half * d[m][i] * d[m][j]);
            }
        }
    }

    // Taylor coefficients of every non-empty piece from the B-spline coefficients.
    template <class Column>
    void to_pieces(const std::vector<double>& knots, std::size_t first, std::size_t last, const Eigen::VectorXd& c,
                   const Column& column) {
        const int p = degree_;
        for (std::size_t k = first; k < last; ++k) {
            if (!(knots[k + 1] > knots[k])) continue;
            breaks_.push_back(knots[k]);
            const detail::BasisDerivatives d = detail::basis_derivatives(knots, k, knots[k], p, p);
            double factorial = 1.0;
            for (int r = 0; r <= p; ++r) {
                if (r > 0) factorial *= r;
                double sum = 0.0;
                for (int j = 0; j <= p; ++j) sum += d[r][j] * c(static_cast<Eigen::Index>(column(k, j)));
                taylor_.push_back(sum / factorial);
            }
        }
        breaks_.push_back(knots[last]);
    }

    void finish() {
        const auto f = [this](double t) { return evaluate(t); };
        peaks_ = detail::find_lift_peaks(f, breaks_, 8);
        if (periodic_)
            for (LiftPeak* q : {&peaks_.velocity, &peaks_.acceleration, &peaks_.jerk})
                if (q->theta >= period) q->theta -= period;
        range_ = detail::find_lift_range(f, breaks_, 8);
        base_ = evaluate(origin()).h;
        if (!periodic_) base_ = h_.front();  // imposed exactly; keeps h_start + lift exact
    }

    // Knots at the table points, extended periodically; coefficient j + N is coefficient j.
    void fit_periodic() {
        const std::size_t n = theta_.size(), p = static_cast<std::size_t>(degree_);
        std::vector<double> knots(n + 2 * p + 1);
        for (std::size_t k = 0; k < knots.size(); ++k) {
            const long i = static_cast<long>(k) - static_cast<long>(p);
            const long wraps = i < 0 ? -1 : i / static_cast<long>(n);
            knots[k] = theta_[static_cast<std::size_t>(i - wraps * static_cast<long>(n))] +
                       period * static_cast<double>(wraps);
        }
        const auto column = [n, p](std::size_t span, int j) {
            return static_cast<Eigen::Index>((span - p + static_cast<std::size_t>(j)) % n);
        };
        const Eigen::Index size = static_cast<Eigen::Index>(n);
        Triplets rows;  // collocation: s(theta_i) = sum_j B_j(theta_i) c_j
        for (std::size_t i = 0; i < n; ++i) {
            const detail::BasisDerivatives d = detail::basis_derivatives(knots, i + p, theta_[i], degree_, 0);
            for (int j = 0; j <= degree_; ++j)
                rows.emplace_back(static_cast<Eigen::Index>(i), column(i + p, j), d[0][j]);
        }
        const Eigen::Map<const Eigen::VectorXd> y(h_.data(), size);
        Eigen::SparseMatrix<double> b(size, size);
        b.setFromTriplets(rows.begin(), rows.end());
        Eigen::VectorXd c;
        if (smoothing_ == 0.0) {
            c = solve(b, y);
        } else {
            Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(b.transpose()) * b;
            Triplets penalty;
            add_penalty(penalty, knots, p, p + n, column);
            Eigen::SparseMatrix<double> omega(size, size);
            omega.setFromTriplets(penalty.begin(), penalty.end());
            normal += omega;
            c = solve(normal, b.transpose() * y);
        }
        to_pieces(knots, p, p + n, c, column);
        finish();
    }

    // Clamped knots (degree + 1 at each end), interior knots by averaging the data sites.
    void fit_segment() {
        const std::size_t p = static_cast<std::size_t>(degree_), points = theta_.size();
        const std::size_t ns = start_derivatives_.size(), ne = end_derivatives_.size();
        struct Condition {
            double theta;
            int order;
            double value;
        };
        std::vector<Condition> conditions;
        conditions.push_back({theta_.front(), 0, h_.front()});
        for (std::size_t k = 0; k < ns; ++k)
            conditions.push_back({theta_.front(), static_cast<int>(k + 1), start_derivatives_[k]});
        for (std::size_t i = 1; i + 1 < points; ++i) conditions.push_back({theta_[i], 0, h_[i]});
        conditions.push_back({theta_.back(), 0, h_.back()});
        for (std::size_t k = 0; k < ne; ++k)
            conditions.push_back({theta_.back(), static_cast<int>(k + 1), end_derivatives_[k]});
        const std::size_t n = conditions.size();  // basis functions
        std::vector<double> sites;
        for (const Condition& q : conditions) sites.push_back(q.theta);
        std::sort(sites.begin(), sites.end());
        std::vector<double> knots(p + 1, theta_.front());
        for (std::size_t j = 0; j + p + 1 < n; ++j) {
            double sum = 0.0;
            for (std::size_t i = j + 1; i <= j + p; ++i) sum += sites[i];
            knots.push_back(sum / static_cast<double>(p));
        }
        knots.insert(knots.end(), p + 1, theta_.back());
        const auto column = [p](std::size_t span, int j) {
            return static_cast<Eigen::Index>(span - p + static_cast<std::size_t>(j));
        };
        const auto add_row = [&](Triplets& t, Eigen::Index row, const Condition& q) {
            const std::size_t span = detail::find_knot_span(knots, degree_, n, q.theta);
            const detail::BasisDerivatives d = detail::basis_derivatives(knots, span, q.theta, degree_, q.order);
            for (int j = 0; j <= degree_; ++j)
                t.emplace_back(row, column(span, j), d[static_cast<std::size_t>(q.order)][j]);
        };
        const Eigen::Index size = static_cast<Eigen::Index>(n);
        Eigen::VectorXd c;
        if (smoothing_ == 0.0) {
            Triplets rows;
            Eigen::VectorXd rhs(size);
            for (std::size_t i = 0; i < n; ++i) {
                add_row(rows, static_cast<Eigen::Index>(i), conditions[i]);
                rhs(static_cast<Eigen::Index>(i)) = conditions[i].value;
            }
            Eigen::SparseMatrix<double> a(size, size);
            a.setFromTriplets(rows.begin(), rows.end());
            c = solve(a, rhs);
        } else {
            // Minimize |B c - y|^2 + lambda c' Omega c subject to the end conditions C c = d (KKT system).
            Triplets fit_rows, constraint_rows;
            std::vector<double> y, d;
            for (const Condition& q : conditions) {
                const bool imposed = q.theta == theta_.front() || q.theta == theta_.back();
                if (imposed) {
                    add_row(constraint_rows, static_cast<Eigen::Index>(d.size()), q);
                    d.push_back(q.value);
                } else {
                    add_row(fit_rows, static_cast<Eigen::Index>(y.size()), q);
                    y.push_back(q.value);
                }
            }
            const Eigen::Index fits = static_cast<Eigen::Index>(y.size()),
                               imposed = static_cast<Eigen::Index>(d.size());
            Eigen::SparseMatrix<double> b(fits, size), constraints(imposed, size);
            b.setFromTriplets(fit_rows.begin(), fit_rows.end());
            constraints.setFromTriplets(constraint_rows.begin(), constraint_rows.end());
            const Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(b.transpose()) * b;
            Triplets kkt;
            for (Eigen::Index k = 0; k < normal.outerSize(); ++k)
                for (Eigen::SparseMatrix<double>::InnerIterator it(normal, k); it; ++it)
                    kkt.emplace_back(it.row(), it.col(), it.value());
            add_penalty(kkt, knots, p, n, column);
            for (Eigen::Index k = 0; k < constraints.outerSize(); ++k)
                for (Eigen::SparseMatrix<double>::InnerIterator it(constraints, k); it; ++it) {
                    kkt.emplace_back(size + it.row(), it.col(), it.value());
                    kkt.emplace_back(it.col(), size + it.row(), it.value());
                }
            Eigen::SparseMatrix<double> a(size + imposed, size + imposed);
            a.setFromTriplets(kkt.begin(), kkt.end());
            Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size + imposed);
            rhs.head(size) = b.transpose() * Eigen::Map<const Eigen::VectorXd>(y.data(), fits);
            rhs.tail(imposed) = Eigen::Map<const Eigen::VectorXd>(d.data(), imposed);
            c = solve(a, rhs).head(size);
        }
        to_pieces(knots, p, n, c, column);
        finish();
    }

    bool periodic_;
    int degree_;
    double smoothing_;
    std::vector<double> theta_, h_, start_derivatives_, end_derivatives_;
    std::vector<double> breaks_;  // piece boundaries, one more than pieces
    std::vector<double> taylor_;  // per piece, degree + 1 values: s^(r)(left end) / r!
    double base_ = 0.0;           // s(origin)
    LiftPeaks peaks_;
    std::pair<double, double> range_{0.0, 0.0};  // lowest, highest s (m)
};

}  // namespace camfollower
