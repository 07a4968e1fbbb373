// SPDX-License-Identifier: BSD-3-Clause
// Manufacturing error of a cam, as a lift error e(theta): the deviation of the follower lift from the
// design lift that a cam-measuring machine reports when it probes with the follower's own roller or
// face (m; positive = lift higher). It belongs to the cam, so MotionProgram::with_profile_error adds it
// to the lift and every user of MotionProgram::evaluate (contact, undercut and pressure-angle
// checks) sees it.
//
// A ProfileError is an immutable sum of components, each periodic in theta (rad, period 2 pi):
// - waviness:  e = A cos(k theta + phi), integer order k >= 1;
// - dent:      e = -d (1 - x^2)^4 for |x| < 1, x = wrap(theta - centre) / (w / 2), 0 outside; d > 0
//              is material missing (lift lower), d < 0 a bump. The polynomial makes e, e', e'', e'''
//              vanish at the edges, so the jerk stays continuous (C3);
// - Fourier:   e = mean + sum_k a_k cos(k theta) + b_k sin(k theta), k = 1..K; table() fits one to
//              measured points by least squares.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "camfollower/detail/linear_solvers.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/laws.hpp"  // pi

namespace camfollower {

// e and its cam-angle derivatives at one theta (m, m/rad, m/rad^2, m/rad^3).
struct LiftError {
    double e = 0.0, de = 0.0, d2e = 0.0, d3e = 0.0;
};

class ProfileError {
public:
    struct Waviness {
        double amplitude;  // A, m
        int order;         // k, waves per revolution
        double phase;      // phi, rad
    };
    struct Dent {
        double centre;  // rad, in [0, 2 pi)
        double width;   // w, rad, in (0, pi]
        double depth;   // d, m; > 0 material missing
    };
    struct Fourier {
        double mean;              // m
        std::vector<double> cos;  // a_1..a_K, m
        std::vector<double> sin;  // b_1..b_K, m
    };
    using Component = std::variant<Waviness, Dent, Fourier>;

    // Sampling density that resolves a harmonic component: points per period of its highest harmonic.
    static constexpr double samples_per_period = 32.0;

    ProfileError() = default;  // no error

    static constexpr double min_dent_width = 1e-6;  // rad

    static ProfileError waviness(double amplitude, int order, double phase = 0.0) {
        detail::require_finite(amplitude, "waviness amplitude (m)");
        if (order < 1) detail::fail("waviness order must be an integer >= 1 (waves per revolution), got ", order);
        detail::require_finite(phase, "waviness phase (rad)");
        return ProfileError(Waviness{amplitude, order, phase});
    }

    static ProfileError dent(double centre, double width, double depth) {
        detail::require_finite(centre, "dent centre (rad)");
        // The dent's slopes grow as depth / width^k: below min_dent_width its derivatives overflow.
        if (!(std::isfinite(width) && width >= min_dent_width && width <= pi))
            detail::fail("dent width must be in [", min_dent_width, " rad, 180 deg], got ", width * 180.0 / pi,
                         " deg (", width, " rad)");
        detail::require_finite(depth, "dent depth (m)");
        return ProfileError(Dent{wrap(centre), width, depth});
    }

    static ProfileError fourier(double mean, std::vector<double> cos, std::vector<double> sin) {
        detail::require_finite(mean, "Fourier mean (m)");
        if (cos.size() != sin.size())
            detail::fail("Fourier cos and sin must have the same length (harmonics 1..K), got ", cos.size(), " and ",
                         sin.size());
        for (std::size_t k = 0; k < cos.size(); ++k)
            if (!std::isfinite(cos[k]) || !std::isfinite(sin[k]))
                detail::fail("Fourier coefficients of harmonic ", k + 1, " must be finite, got cos ", cos[k], ", sin ",
                             sin[k]);
        return ProfileError(Fourier{mean, std::move(cos), std::move(sin)});
    }

    // Least-squares trigonometric fit of a measured table: N >= 3 points, theta strictly increasing in
    // [0, 2 pi). max_harmonic in [1, floor((N - 1) / 2)], by default the upper end (interpolation for
    // an odd number of equally spaced points); a lower one smooths a noisy table. Equally spaced
    // points cost O(N K), others a QR of N x (2K + 1); evaluation costs O(K) per theta.
    static ProfileError table(const std::vector<double>& theta, const std::vector<double>& error,
                              std::optional<int> max_harmonic = std::nullopt) {
        const std::size_t n = theta.size();
        if (error.size() != n)
            detail::fail("lift-error table: theta and error must have the same length, got ", n, " and ", error.size());
        if (n < 3) detail::fail("lift-error table: needs at least 3 points, got ", n);
        for (std::size_t i = 0; i < n; ++i) {
            if (!std::isfinite(theta[i]) || !std::isfinite(error[i]))
                detail::fail("lift-error table: point ", i, " must be finite, got theta = ", theta[i],
                             " rad, error = ", error[i], " m");
            const bool increasing = i == 0 ? theta[i] >= 0.0 : theta[i] > theta[i - 1];
            if (!increasing || theta[i] >= 2.0 * pi)
                detail::fail("lift-error table: theta must be strictly increasing in [0, 360) deg; point ", i,
                             " is at ", theta[i] * 180.0 / pi, " deg",
                             i > 0 ? detail::concat(" after ", theta[i - 1] * 180.0 / pi, " deg") : "");
        }
        const int limit = static_cast<int>((n - 1) / 2);
        const int K = max_harmonic.value_or(limit);
        if (K < 1 || K > limit)
            detail::fail("lift-error table: max_harmonic must be in [1, ", limit, "] (floor((N - 1) / 2) for N = ", n,
                         " points), got ", K);
        return equally_spaced(theta) ? fit_equally_spaced(theta, error, K) : fit_least_squares(theta, error, K);
    }

    ProfileError operator+(const ProfileError& other) const {
        ProfileError sum = *this;
        sum.components_.insert(sum.components_.end(), other.components_.begin(), other.components_.end());
        return sum;
    }

    const std::vector<Component>& components() const { return components_; }
    bool empty() const { return components_.empty(); }

    LiftError evaluate(double theta) const {
        if (!std::isfinite(theta)) detail::fail("theta must be finite, got ", theta);
        const double t = wrap(theta);
        LiftError sum;
        for (const Component& c : components_) {
            const LiftError v = std::visit([t](const auto& x) { return value(x, t); }, c);
            sum.e += v.e, sum.de += v.de, sum.d2e += v.d2e, sum.d3e += v.d3e;
        }
        return sum;
    }

    // Angles (rad, ascending, in [0, 2 pi)) a sampled search must visit: dent centres and edges, where
    // a narrow dent would otherwise fall between samples and where its smoothness breaks (C3 edges).
    std::vector<double> features() const {
        std::vector<double> out;
        for (const Component& c : components_)
            if (const Dent* d = std::get_if<Dent>(&c))
                for (double x : {d->centre - 0.5 * d->width, d->centre, d->centre + 0.5 * d->width})
                    out.push_back(wrap(x));
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

    // Largest sampling step (rad) that resolves the harmonic components; +inf without any. Dents need
    // no global step: their features split a search, so each half of a dent is a piece of its own,
    // sampled as densely as a whole program segment.
    double sampling_step() const {
        double step = std::numeric_limits<double>::infinity();
        for (const Component& c : components_) {
            if (const Waviness* w = std::get_if<Waviness>(&c))
                step = std::min(step, 2.0 * pi / (samples_per_period * w->order));
            else if (const Fourier* f = std::get_if<Fourier>(&c); f && !f->cos.empty())
                step = std::min(step, 2.0 * pi / (samples_per_period * static_cast<double>(f->cos.size())));
        }
        return step;
    }

private:
    explicit ProfileError(Component c) : components_{std::move(c)} {}

    static double wrap(double theta) {
        double t = std::fmod(theta, 2.0 * pi);
        if (t < 0.0) t += 2.0 * pi;
        return t >= 2.0 * pi ? 0.0 : t;
    }

    static LiftError value(const Waviness& w, double t) {
        const double k = w.order, c = std::cos(k * t + w.phase), s = std::sin(k * t + w.phase);
        const double a = w.amplitude;
        return {a * c, -a * k * s, -a * k * k * c, a * k * k * k * s};
    }

    static LiftError value(const Dent& d, double t) {
        double dx = t - d.centre;  // signed, in (-pi, pi]
        if (dx > pi) dx -= 2.0 * pi;
        else if (dx <= -pi) dx += 2.0 * pi;
        const double s = 2.0 / d.width, x = dx * s;
        if (std::abs(x) >= 1.0) return {};
        const double u = 1.0 - x * x, u2 = u * u;
        return {-d.depth * u2 * u2, 8.0 * d.depth * x * u2 * u * s, 8.0 * d.depth * u2 * (1.0 - 7.0 * x * x) * s * s,
                48.0 * d.depth * u * x * (7.0 * x * x - 3.0) * s * s * s};
    }

    // cos(k t), sin(k t) by the rotation recurrence, restarted every 32 harmonics so the rounding error
    // stays at a few ulps whatever K.
    static LiftError value(const Fourier& f, double t) {
        LiftError v{f.mean, 0.0, 0.0, 0.0};
        const double c1 = std::cos(t), s1 = std::sin(t);
        double ck = c1, sk = s1;
        for (std::size_t i = 0; i < f.cos.size(); ++i) {
            const double k = static_cast<double>(i + 1);
            if (i % 32 == 0) ck = std::cos(k * t), sk = std::sin(k * t);
            const double p = f.cos[i] * ck + f.sin[i] * sk;  // a cos + b sin
            const double q = f.sin[i] * ck - f.cos[i] * sk;  // its derivative / k
            v.e += p, v.de += k * q, v.d2e -= k * k * p, v.d3e -= k * k * k * q;
            const double next_c = ck * c1 - sk * s1;
            sk = sk * c1 + ck * s1, ck = next_c;
        }
        return v;
    }

    // theta_i = theta_0 + 2 pi i / N: the harmonics k < N/2 are then orthogonal over the points, so the
    // least-squares coefficients are the discrete Fourier sums (O(N K) instead of a QR's O(N K^2)).
    static bool equally_spaced(const std::vector<double>& theta) {
        const double h = 2.0 * pi / static_cast<double>(theta.size());
        for (std::size_t i = 1; i < theta.size(); ++i)
            if (std::abs(theta[i] - theta[0] - h * static_cast<double>(i)) > 1e-12) return false;
        return true;
    }

    static ProfileError fit_equally_spaced(const std::vector<double>& theta, const std::vector<double>& error, int K) {
        const double n = static_cast<double>(theta.size());
        const std::size_t harmonics = static_cast<std::size_t>(K);
        Fourier f{0.0, std::vector<double>(harmonics, 0.0), std::vector<double>(harmonics, 0.0)};
        for (std::size_t i = 0; i < theta.size(); ++i) {
            f.mean += error[i] / n;
            for (int k = 1; k <= K; ++k) {
                f.cos[k - 1] += 2.0 / n * error[i] * std::cos(k * theta[i]);
                f.sin[k - 1] += 2.0 / n * error[i] * std::sin(k * theta[i]);
            }
        }
        return ProfileError(std::move(f));
    }

    static ProfileError fit_least_squares(const std::vector<double>& theta, const std::vector<double>& error, int K) {
        const Eigen::Index n = static_cast<Eigen::Index>(theta.size()), cols = 2 * K + 1;
        Eigen::MatrixXd A(n, cols);
        for (Eigen::Index i = 0; i < n; ++i) {
            A(i, 0) = 1.0;
            for (int k = 1; k <= K; ++k) {
                A(i, 2 * k - 1) = std::cos(k * theta[i]);
                A(i, 2 * k) = std::sin(k * theta[i]);
            }
        }
        // Points crowded into part of the revolution leave high harmonics undetermined: refuse rather
        // than return wild coefficients.
        Eigen::VectorXd x;
        const Eigen::Index rank =
            detail::qr_least_squares<double>(A, Eigen::Map<const Eigen::VectorXd>(error.data(), n), 1e-10, x);
        if (rank < cols)
            detail::fail("lift-error table: the points do not determine harmonics up to max_harmonic = ", K,
                         " (numerical rank ", rank, " < ", cols,
                         "): spread the points over the revolution or lower max_harmonic");
        const std::size_t harmonics = static_cast<std::size_t>(K);
        Fourier f{x(0), std::vector<double>(harmonics), std::vector<double>(harmonics)};
        for (int k = 1; k <= K; ++k) f.cos[k - 1] = x(2 * k - 1), f.sin[k - 1] = x(2 * k);
        return ProfileError(std::move(f));
    }

    std::vector<Component> components_;
};

}  // namespace camfollower
