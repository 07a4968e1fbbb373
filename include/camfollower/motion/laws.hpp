// SPDX-License-Identifier: BSD-3-Clause
// Normalized cam motion laws: S(x), V = dS/dx, A = d2S/dx2, J = d3S/dx3 on x in [0, 1],
// S(0) = 0, S(1) = 1, plus their peak coefficients C_v, C_a, C_j (peaks of |V|, |A|, |J|).
//
// The sine-constant-cosine acceleration family (Norton, "Cam Design and Manufacturing Handbook",
// SCCA) is parameterized by b + c + d = 1:
//   [0, b/2]           A = Ca sin(pi x / b)              quarter sine rising to Ca
//   [b/2, (1-d)/2]     A = Ca                            constant
//   [(1-d)/2, 1/2]     A = Ca cos(pi (x - (1-d)/2) / d)  half of a cosine falling through zero
// and A(1 - x) = -A(x) beyond 1/2. b = 1/4, d = 1/4 is the modified trapezoid, b = 1/4, d = 3/4 the
// modified sine, b = d = 1/2 cycloidal, d = 1 simple harmonic, c = 1 constant acceleration.
//
// Custom laws (LawKind::spline, LawKind::polynomial) carry a user-defined lift in physical units, shared
// and immutable (a lift table as a B-spline, lift_spline.hpp; a polynomial from boundary conditions,
// lift_polynomial.hpp). They are evaluated relative to their segment's start with evaluate_lift(u)
// (m, m/rad^k): their net lift may be zero, so the normalized S(0) = 0, S(1) = 1 form does not apply
// in general. evaluate(x) and peaks() still give the normalized form S = (h - h_start) / lift when the
// net lift is not zero.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "camfollower/error.hpp"
#include "camfollower/motion/follower_motion.hpp"
#include "camfollower/motion/lift_peaks.hpp"
#include "camfollower/constants.hpp"
#include "camfollower/motion/lift_polynomial.hpp"
#include "camfollower/motion/lift_spline.hpp"

namespace camfollower {

struct LawValue {
    double S, V, A, J;
};

struct PeakCoefficients {
    double velocity;      // C_v = max |V|
    double acceleration;  // C_a = max |A|
    double jerk;          // C_j = max |J| (+inf where A jumps inside the segment)
};

enum class LawKind {
    dwell,
    simple_harmonic,
    cycloidal,
    sine_constant_cosine,
    polynomial_345,
    polynomial_4567,
    constant_acceleration,
    spline,     // a lift table as a B-spline (LiftSpline)
    polynomial  // a polynomial from boundary conditions (LiftPolynomial)
};

class MotionLaw {
public:
    static MotionLaw dwell() { return MotionLaw(LawKind::dwell); }
    static MotionLaw simple_harmonic() { return MotionLaw(LawKind::simple_harmonic); }
    static MotionLaw cycloidal() { return MotionLaw(LawKind::cycloidal); }
    static MotionLaw polynomial_345() { return MotionLaw(LawKind::polynomial_345); }
    static MotionLaw polynomial_4567() { return MotionLaw(LawKind::polynomial_4567); }
    static MotionLaw constant_acceleration() { return MotionLaw(LawKind::constant_acceleration); }
    static constexpr double min_fraction = 1e-6;
    static MotionLaw modified_trapezoid() { return sine_constant_cosine(0.25, 0.5, 0.25); }
    static MotionLaw modified_sine() { return sine_constant_cosine(0.25, 0.0, 0.75); }

    // b: total sine fraction, c: total constant fraction, d: cosine fraction; each in [0, 1],
    // b + c + d = 1 (to 1e-12).
    static MotionLaw sine_constant_cosine(double b, double c, double d) {
        detail::require_in_range(b, 0.0, 1.0, "b (sine fraction)");
        detail::require_in_range(c, 0.0, 1.0, "c (constant fraction)");
        detail::require_in_range(d, 0.0, 1.0, "d (cosine fraction)");
        if (std::abs(b + c + d - 1.0) > 1e-12) detail::fail("b + c + d must equal 1 (to 1e-12), got ", b + c + d);
        // A part's jerk grows as 1 / fraction^2: a sliver of a part is an overflow, not a law.
        for (const auto& [value, name] :
             {std::pair{b, "b (sine fraction)"}, {c, "c (constant fraction)"}, {d, "d (cosine fraction)"}})
            if (value != 0.0 && value < min_fraction)
                detail::fail(name, " must be 0 or at least ", min_fraction, ", got ", value);
        MotionLaw law(LawKind::sine_constant_cosine);
        law.b_ = b;
        law.c_ = c;
        law.d_ = d;
        // Unit-Ca integrals up to x = 1/2 (see header comment); S(1/2) = 1/2 fixes Ca.
        law.v1_ = b / pi;
        law.s1_ = b * b / (2.0 * pi) - b * b / (pi * pi);
        law.v2_ = law.v1_ + c / 2.0;
        law.s2_ = law.s1_ + law.v1_ * c / 2.0 + c * c / 8.0;
        const double s_half = law.s2_ + law.v2_ * d / 2.0 + d * d / (pi * pi);
        law.ca_ = 1.0 / (2.0 * s_half);
        return law;
    }

    // A user-defined lift: a spline (a segment's, or a periodic one spanning a whole program).
    static MotionLaw from_spline(std::shared_ptr<const LiftSpline> spline) {
        if (!spline) detail::fail("spline must not be null");
        MotionLaw law(LawKind::spline);
        law.spline_ = std::move(spline);
        return law;
    }
    static MotionLaw from_polynomial(std::shared_ptr<const LiftPolynomial> polynomial) {
        if (!polynomial) detail::fail("polynomial must not be null");
        MotionLaw law(LawKind::polynomial);
        law.polynomial_ = std::move(polynomial);
        return law;
    }

    LawKind kind() const { return kind_; }
    bool is_custom() const { return kind_ >= LawKind::spline; }  // custom kinds come last
    // The custom lift's data; nullptr for other kinds.
    const LiftSpline* spline() const { return spline_.get(); }
    const LiftPolynomial* polynomial() const { return polynomial_.get(); }
    // A custom law's own span (rad) and net lift h(end) - h(start) (m): its segment must match them.
    double custom_span() const { return spline_ ? spline_->span() : polynomial_ ? polynomial_->span() : 0.0; }
    double custom_lift() const { return spline_ ? spline_->net_lift() : polynomial_ ? polynomial_->net_lift() : 0.0; }

    // A custom law's lift relative to its segment's start, h(theta_start + u) - h(theta_start), and its
    // derivatives (m, m/rad^k), u in [0, custom_span()].
    FollowerMotion evaluate_lift(double u) const {
        if (spline_) return spline_->relative(u);
        if (polynomial_) return polynomial_->relative(u);
        detail::fail("evaluate_lift is for spline and polynomial laws; ", name(),
                     " is normalized: use evaluate(x) scaled by the segment's lift and span");
    }

    // A custom law's peaks of |h'|, |h''|, |h'''| (m/rad^k), each angle as an offset from the segment
    // start (rad); computed once when the law is built.
    LiftPeaks lift_peaks() const {
        if (!is_custom())
            detail::fail("lift_peaks is for spline and polynomial laws; for ", name(),
                         " use peaks() (C_v, C_a, C_j) times lift / span^k");
        LiftPeaks p = spline_ ? spline_->peaks() : polynomial_->peaks();
        const double origin = spline_ ? spline_->origin() : polynomial_->origin();
        for (LiftPeak* q : {&p.velocity, &p.acceleration, &p.jerk}) q->theta -= origin;
        return p;
    }
    double b() const { return b_; }
    double c() const { return c_; }
    double d() const { return d_; }
    bool is_dwell() const { return kind_ == LawKind::dwell; }

    std::string name() const {
        switch (kind_) {
            case LawKind::dwell: return "dwell";
            case LawKind::simple_harmonic: return "simple_harmonic";
            case LawKind::cycloidal: return "cycloidal";
            case LawKind::polynomial_345: return "polynomial_345";
            case LawKind::polynomial_4567: return "polynomial_4567";
            case LawKind::constant_acceleration: return "constant_acceleration";
            case LawKind::sine_constant_cosine:
                return detail::concat("sine_constant_cosine(b=", b_, ", c=", c_, ", d=", d_, ")");
            case LawKind::spline: return spline_->name();
            case LawKind::polynomial: return polynomial_->name();
        }
        return "unknown";
    }

    // x must lie in [0, 1]; a rounding excursion of 1e-12 is clamped.
    LawValue evaluate(double x) const {
        if (!(x >= -1e-12 && x <= 1.0 + 1e-12)) detail::fail("x must be in [0, 1], got ", x);
        x = std::fmin(std::fmax(x, 0.0), 1.0);
        switch (kind_) {
            case LawKind::dwell: return {0.0, 0.0, 0.0, 0.0};
            case LawKind::simple_harmonic: {
                const double s = std::sin(pi * x), c = std::cos(pi * x);
                return {0.5 * (1.0 - c), 0.5 * pi * s, 0.5 * pi * pi * c, -0.5 * pi * pi * pi * s};
            }
            case LawKind::cycloidal: {
                const double s = std::sin(2.0 * pi * x), c = std::cos(2.0 * pi * x);
                return {x - s / (2.0 * pi), 1.0 - c, 2.0 * pi * s, 4.0 * pi * pi * c};
            }
            case LawKind::polynomial_345: {
                const double x2 = x * x, u = 1.0 - x;
                return {x2 * x * (10.0 - 15.0 * x + 6.0 * x2), 30.0 * x2 * u * u, 60.0 * x * u * (1.0 - 2.0 * x),
                        60.0 * (1.0 - 6.0 * x + 6.0 * x2)};
            }
            case LawKind::polynomial_4567: {
                const double x2 = x * x, u = 1.0 - x, xu = x * u;
                return {x2 * x2 * (35.0 - 84.0 * x + 70.0 * x2 - 20.0 * x2 * x), 140.0 * xu * xu * xu,
                        420.0 * xu * xu * (1.0 - 2.0 * x), 840.0 * xu * (1.0 - 5.0 * x + 5.0 * x2)};
            }
            case LawKind::constant_acceleration:
                if (x <= 0.5) return {2.0 * x * x, 4.0 * x, 4.0, 0.0};
                return {1.0 - 2.0 * (1.0 - x) * (1.0 - x), 4.0 * (1.0 - x), -4.0, 0.0};
            case LawKind::sine_constant_cosine:
                if (x <= 0.5) return scc_first_half(x);
                {
                    const LawValue m = scc_first_half(1.0 - x);
                    return {1.0 - m.S, m.V, -m.A, m.J};
                }
            case LawKind::spline:
            case LawKind::polynomial: return custom_normalized(x);
        }
        return {0.0, 0.0, 0.0, 0.0};
    }

    // Peaks from the closed-form location of each extremum. A custom law's come from its numerical
    // lift_peaks() in the normalized form: C_v = max|h'| beta / |L|, C_a = max|h''| beta^2 / |L|,
    // C_j = max|h'''| beta^3 / |L| (beta its span, L its net lift; +inf when L = 0 and the peak is not).
    PeakCoefficients peaks() const {
        const double inf = std::numeric_limits<double>::infinity();
        switch (kind_) {
            case LawKind::dwell: return {0.0, 0.0, 0.0};
            case LawKind::simple_harmonic: return {pi / 2.0, pi * pi / 2.0, pi * pi * pi / 2.0};
            case LawKind::cycloidal: return {2.0, 2.0 * pi, 4.0 * pi * pi};
            case LawKind::polynomial_345: {
                const double x_amax = (3.0 - std::sqrt(3.0)) / 6.0;  // root of J = 0
                return {evaluate(0.5).V, std::abs(evaluate(x_amax).A), std::abs(evaluate(0.0).J)};
            }
            case LawKind::polynomial_4567: {
                const double x_amax = (5.0 - std::sqrt(5.0)) / 10.0;  // root of 1 - 5x + 5x^2
                return {evaluate(0.5).V, std::abs(evaluate(x_amax).A), std::abs(evaluate(0.5).J)};
            }
            case LawKind::constant_acceleration: return {2.0, 4.0, inf};  // A jumps at x = 1/2
            case LawKind::sine_constant_cosine: {
                const double cv = ca_ * (b_ / pi + c_ / 2.0 + d_ / pi);
                double cj = inf;  // d = 0: A jumps from +Ca to -Ca at x = 1/2
                if (d_ > 0.0) {
                    const double shortest = b_ > 0.0 ? std::fmin(b_, d_) : d_;
                    cj = ca_ * pi / shortest;
                }
                return {cv, ca_, cj};
            }
            case LawKind::spline:
            case LawKind::polynomial: {
                const LiftPeaks p = lift_peaks();
                const double beta = custom_span(), lift = std::abs(custom_lift());
                const auto normalized = [&](double peak, int power) {
                    if (peak == 0.0) return 0.0;
                    return lift > 0.0 ? peak * std::pow(beta, power) / lift : inf;
                };
                return {normalized(p.velocity.value, 1), normalized(p.acceleration.value, 2),
                        normalized(p.jerk.value, 3)};
            }
        }
        return {0.0, 0.0, 0.0};
    }

    // Whether S, V and A are continuous at both ends (A(0) = A(1) = 0 and the law itself C2). A custom
    // law: C2 inside (a spline of degree >= 3, any polynomial) and |h''| at both ends within 1e-9 of its
    // scale max(peak |h''|, |L| / beta^2).
    bool has_zero_end_acceleration() const {
        switch (kind_) {
            case LawKind::simple_harmonic:
            case LawKind::constant_acceleration: return false;
            case LawKind::sine_constant_cosine: return b_ > 0.0;
            case LawKind::spline:
            case LawKind::polynomial: {
                if (spline_ && spline_->degree() < 3) return false;
                const double beta = custom_span();
                const double scale =
                    std::fmax(lift_peaks().acceleration.value, std::abs(custom_lift()) / (beta * beta));
                const double tolerance = 1e-9 * scale;
                return std::abs(evaluate_lift(0.0).d2h) <= tolerance && std::abs(evaluate_lift(beta).d2h) <= tolerance;
            }
            default: return true;
        }
    }

private:
    explicit MotionLaw(LawKind kind) : kind_(kind) {}

    LawValue custom_normalized(double x) const {
        const double beta = custom_span(), lift = custom_lift();
        if (lift == 0.0)
            detail::fail("evaluate(x): the ", name(), " law gains no net lift, so it has no normalized form S(x); ",
                         "use evaluate_lift (m, m/rad^k)");
        const FollowerMotion m = evaluate_lift(x * beta);
        return {m.h / lift, m.dh * beta / lift, m.d2h * beta * beta / lift, m.d3h * beta * beta * beta / lift};
    }

    LawValue scc_first_half(double x) const {
        const double x1 = b_ / 2.0, x2 = (1.0 - d_) / 2.0;
        if (b_ > 0.0 && x <= x1) {
            const double u = pi * x / b_;
            const double k = b_ / pi;
            return {ca_ * k * (x - k * std::sin(u)), ca_ * k * (1.0 - std::cos(u)), ca_ * std::sin(u),
                    ca_ / k * std::cos(u)};
        }
        if (d_ == 0.0 || x <= x2) {
            const double t = x - x1;
            return {ca_ * (s1_ + v1_ * t + 0.5 * t * t), ca_ * (v1_ + t), ca_, 0.0};
        }
        const double t = x - x2, u = pi * t / d_, k = d_ / pi;
        return {ca_ * (s2_ + v2_ * t + k * k * (1.0 - std::cos(u))), ca_ * (v2_ + k * std::sin(u)), ca_ * std::cos(u),
                -ca_ / k * std::sin(u)};
    }

    LawKind kind_;
    double b_ = 0.0, c_ = 0.0, d_ = 0.0;
    double ca_ = 0.0, s1_ = 0.0, v1_ = 0.0, s2_ = 0.0, v2_ = 0.0;
    std::shared_ptr<const LiftSpline> spline_;          // LawKind::spline only
    std::shared_ptr<const LiftPolynomial> polynomial_;  // LawKind::polynomial only
};

}  // namespace camfollower
