// SPDX-License-Identifier: BSD-3-Clause
// A polynomial lift from boundary conditions ("polydyne"-style general polynomial): h, h', h'', ...
// imposed at both ends of a segment and lift values at interior angles. Degree = number of
// conditions - 1. Solved in the normalized variable x = (theta - theta_start) / span, in which the
// system is well scaled; conditions with consecutive derivatives at two ends and distinct interior
// points always have exactly one solution (Hermite-Birkhoff interpolation of this shape is poised), so
// what can go wrong is bad input or too many conditions for double precision (refused by the condition
// number of the system).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "camfollower/constants.hpp"
#include "camfollower/detail/linear_solvers.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/follower_motion.hpp"
#include "camfollower/motion/lift_peaks.hpp"

namespace camfollower {

class LiftPolynomial {
public:
    // Systems with a larger condition number (in x) are refused: the coefficients would carry less
    // than about four significant digits.
    static constexpr double max_condition_number = 1e12;

    // start = {h, h', h'', ...} at theta_start (m, m/rad, ...; at least h), end likewise at theta_end,
    // interior = (theta, h) points strictly inside, each angle once.
    static LiftPolynomial from_conditions(double theta_start, double theta_end, std::vector<double> start,
                                          std::vector<double> end,
                                          std::vector<std::pair<double, double>> interior = {}) {
        detail::require_finite(theta_start, "theta_start (rad)");
        detail::require_finite(theta_end, "theta_end (rad)");
        if (!(theta_end > theta_start))
            detail::fail("theta_end must be > theta_start: the span theta_end - theta_start = ",
                         theta_end - theta_start, " rad must be positive");
        for (auto* side : {&start, &end}) {
            const char* name = side == &start ? "start" : "end";
            if (side->empty()) detail::fail(name, " must hold at least the lift h (m) at theta_", name);
            for (std::size_t k = 0; k < side->size(); ++k)
                if (!std::isfinite((*side)[k]))
                    detail::fail(name, "[", k, "] (derivative of order ", k, ", m/rad^", k, ") must be finite, got ",
                                 (*side)[k]);
        }
        const double span = theta_end - theta_start;
        for (std::size_t i = 0; i < interior.size(); ++i) {
            const auto [theta, h] = interior[i];
            if (!std::isfinite(theta) || !std::isfinite(h))
                detail::fail("interior[", i, "] must be finite, got theta = ", theta, " rad, h = ", h, " m");
            if (!(theta > theta_start && theta < theta_end))
                detail::fail("interior[", i, "]: theta = ", theta * 180.0 / pi, " deg must lie strictly inside (",
                             theta_start * 180.0 / pi, ", ", theta_end * 180.0 / pi, ") deg");
            for (std::size_t j = 0; j < i; ++j)
                if (std::abs(interior[j].first - theta) <= 1e-12 * span)
                    detail::fail("interior[", i, "] repeats the angle of interior[", j, "] (", theta * 180.0 / pi,
                                 " deg): each interior angle may carry one lift");
        }
        LiftPolynomial p(theta_start, theta_end, std::move(start), std::move(end), std::move(interior));
        p.solve();
        return p;
    }

    int degree() const { return static_cast<int>(coefficients_.size()) - 1; }
    double theta_start() const { return theta_start_; }
    double theta_end() const { return theta_end_; }
    const std::vector<double>& start() const { return start_; }
    const std::vector<double>& end() const { return end_; }
    const std::vector<std::pair<double, double>>& interior() const { return interior_; }
    // h = sum_k coefficients[k] x^k, x = (theta - theta_start) / span (m).
    const std::vector<double>& coefficients() const { return coefficients_; }
    // Condition number of the solved system (in x).
    double condition_number() const { return condition_; }

    double origin() const { return theta_start_; }
    double span() const { return theta_end_ - theta_start_; }
    double net_lift() const { return end_.front() - start_.front(); }
    const LiftPeaks& peaks() const { return peaks_; }
    // Lowest and highest lift over the span, relative to the segment start (m).
    std::pair<double, double> relative_range() const {
        return {range_.first - start_.front(), range_.second - start_.front()};
    }
    std::string name() const { return detail::concat("polynomial(degree=", degree(), ")"); }

    // h and its derivatives at an absolute theta in [theta_start, theta_end] (1e-9 rad clamped).
    FollowerMotion evaluate(double theta) const {
        if (!(theta >= theta_start_ - 1e-9 && theta <= theta_end_ + 1e-9))
            detail::fail("theta = ", theta, " rad is outside the polynomial's span [", theta_start_, ", ", theta_end_,
                         "] rad");
        const double beta = span();
        const double x = std::fmin(std::fmax((theta - theta_start_) / beta, 0.0), 1.0);
        const std::size_t n = coefficients_.size();
        double v = coefficients_[n - 1], d1 = 0.0, d2 = 0.0, d3 = 0.0;  // dk accumulates d^k h/dx^k / k!
        for (std::size_t r = n - 1; r-- > 0;) {
            d3 = d3 * x + d2;
            d2 = d2 * x + d1;
            d1 = d1 * x + v;
            v = v * x + coefficients_[r];
        }
        return {v, d1 / beta, 2.0 * d2 / (beta * beta), 6.0 * d3 / (beta * beta * beta)};
    }

    // Relative to its segment: h(theta_start + u) - h(theta_start), u in [0, span] (rad).
    FollowerMotion relative(double u) const {
        FollowerMotion m = evaluate(theta_start_ + u);
        m.h -= start_.front();
        return m;
    }

private:
    LiftPolynomial(double theta_start, double theta_end, std::vector<double> start, std::vector<double> end,
                   std::vector<std::pair<double, double>> interior)
        : theta_start_(theta_start),
          theta_end_(theta_end),
          start_(std::move(start)),
          end_(std::move(end)),
          interior_(std::move(interior)) {}

    // Row for d^r h/dx^r (x0) / r! = beta^r h^(r) / r!: sum_k C(k, r) x0^(k - r) a_k.
    void solve() {
        const Eigen::Index n = static_cast<Eigen::Index>(start_.size() + end_.size() + interior_.size());
        const double beta = span();
        Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
        Eigen::VectorXd rhs(n);
        Eigen::Index row = 0;
        const auto add = [&](double x0, std::size_t order, double value) {
            const Eigen::Index r = static_cast<Eigen::Index>(order);
            double scale = 1.0;  // beta^r / r!
            for (Eigen::Index k = 1; k <= r; ++k) scale *= beta / static_cast<double>(k);
            for (Eigen::Index k = r; k < n; ++k) {
                double binomial = 1.0;  // C(k, r)
                for (Eigen::Index j = 1; j <= r; ++j)
                    binomial *= static_cast<double>(k - r + j) / static_cast<double>(j);
                a(row, k) = binomial * std::pow(x0, static_cast<double>(k - r));
            }
            rhs(row++) = scale * value;
        };
        for (std::size_t k = 0; k < start_.size(); ++k) add(0.0, k, start_[k]);
        for (std::size_t k = 0; k < end_.size(); ++k) add(1.0, k, end_[k]);
        for (const auto& [theta, h] : interior_) add((theta - theta_start_) / beta, 0, h);
        Eigen::VectorXd c;
        condition_ = detail::svd_solve<double>(a, rhs, c);
        if (!(condition_ <= max_condition_number))
            detail::fail("start/end/interior: these ", n, " conditions (a degree-", n - 1,
                         " polynomial) make an ill-conditioned system (condition number ", condition_, " > ",
                         max_condition_number, "); impose fewer derivatives or interior points");
        coefficients_.assign(c.data(), c.data() + n);
        const auto f = [this](double t) { return evaluate(t); };
        const std::size_t samples = static_cast<std::size_t>(std::max<Eigen::Index>(256, 32 * n));
        peaks_ = detail::find_lift_peaks(f, {theta_start_, theta_end_}, samples);
        range_ = detail::find_lift_range(f, {theta_start_, theta_end_}, samples);
    }

    double theta_start_, theta_end_;
    std::vector<double> start_, end_;
    std::vector<std::pair<double, double>> interior_;
    std::vector<double> coefficients_;
    double condition_ = 0.0;
    LiftPeaks peaks_;
    std::pair<double, double> range_{0.0, 0.0};  // lowest, highest h (m)
};

}  // namespace camfollower
