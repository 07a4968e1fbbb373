// SPDX-License-Identifier: BSD-3-Clause
// A cam motion program: segments that tile one revolution, giving the follower lift h(theta) and its
// derivatives with respect to the cam angle (m, m/rad, m/rad^2, m/rad^3). Periodic in theta.
// The program may carry the cam's manufacturing error (profile_error.hpp), added to the design lift.
// Segments carry a built-in normalized law, or a user-defined lift: a table as a B-spline
// (Segment::from_table, or MotionProgram::from_table for a whole periodic program) or a polynomial
// from boundary conditions (Segment::polynomial). continuity() reports the jumps at the boundaries.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "camfollower/constants.hpp"
#include "camfollower/detail/extremum.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/continuity.hpp"
#include "camfollower/motion/follower_motion.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/motion/lift_polynomial.hpp"
#include "camfollower/motion/lift_spline.hpp"
#include "camfollower/motion/profile_error.hpp"

namespace camfollower {

struct Segment {
    MotionLaw law;
    double theta_start;  // rad
    double theta_end;    // rad
    double h_start;      // m, lift at theta_start
    double h_end;        // m, lift at theta_end

    double span() const { return theta_end - theta_start; }
    double lift() const { return h_end - h_start; }

    // The shortest segment: the derivatives h^(k) scale as lift / span^k (a 1e-300 rad rise overflows
    // them), and a span near MotionProgram's snapping tolerance would be set by rounding. 1e-6 rad =
    // 0.2 arc seconds.
    static constexpr double min_span = 1e-6;
    // Boundaries (and a custom law's span) may be off by up to this much (rad).
    static constexpr double angle_tolerance = 1e-9;

    // The segment on its own: finite angles, lifts within reach, a span of at least min_span, a dwell
    // that does not rise, a custom law matching the span and lift. `at` names it in messages;
    // `h_scale`: the lift difference taken as zero (m; negative: from the segment's own levels).
    void validate(const std::string& at = "segment", double h_scale = -1.0) const {
        if (!std::isfinite(theta_start) || !std::isfinite(theta_end))
            detail::fail(at, ".theta_start/theta_end must be finite, got ", theta_start, ", ", theta_end);
        if (!(std::abs(h_start) <= detail::max_part_length && std::abs(h_end) <= detail::max_part_length))
            detail::fail(at, ".h_start/h_end must be in [", -detail::max_part_length, ", ", detail::max_part_length,
                         "] m, got ", h_start, ", ", h_end);
        if (!(span() >= min_span))
            detail::fail(at, " spans ", span(), " rad (", span() * 180.0 / pi,
                         " deg): span theta_end - theta_start must be "
                         "at least ",
                         min_span, " rad");
        if (h_scale < 0.0) h_scale = 1e-12 + 1e-9 * std::max(std::abs(h_start), std::abs(h_end));
        if (law.is_dwell() && std::abs(lift()) > h_scale)
            detail::fail(at, ": a dwell must have h_end == h_start, got a lift of ", lift(), " m");
        if (law.is_custom()) {
            if (std::abs(span() - law.custom_span()) > angle_tolerance)
                detail::fail(at, ": its ", law.name(), " law spans ", law.custom_span() * 180.0 / pi,
                             " deg but the segment spans ", span() * 180.0 / pi,
                             " deg (theta_end - theta_start must match the law)");
            if (std::abs(lift() - law.custom_lift()) > h_scale)
                detail::fail(at, ": its ", law.name(), " law lifts by ", law.custom_lift(),
                             " m but h_end - h_start = ", lift(), " m (the segment's levels must match the law)");
        }
    }

    // A lift table as one segment, a B-spline (lift_spline.hpp): theta absolute (rad, strictly
    // increasing), the segment spans [theta.front(), theta.back()] from h.front() to h.back() (m). The
    // end values and the end derivatives h', h'', ... (m/rad^k, up to degree - 1 per end) are imposed;
    // an empty list means zeros up to degree - 1, so the segment meets a dwell C^(degree-1).
    static Segment from_table(std::vector<double> theta, std::vector<double> h, const SplineOptions& options = {},
                              std::vector<double> start_derivatives = {}, std::vector<double> end_derivatives = {}) {
        auto spline = std::make_shared<const LiftSpline>(LiftSpline::segment(
            std::move(theta), std::move(h), options, std::move(start_derivatives), std::move(end_derivatives)));
        const double a = spline->theta().front(), b = spline->theta().back();
        const double h0 = spline->h().front(), h1 = spline->h().back();
        return Segment{MotionLaw::from_spline(std::move(spline)), a, b, h0, h1};
    }

    // The polynomial meeting start = {h, h', h'', ...} at theta_start, end likewise at theta_end (m,
    // m/rad^k; at least h each) and passing through the interior (theta, h) points (lift_polynomial.hpp).
    // Degree = number of conditions - 1: {h0, 0, 0} / {h1, 0, 0} gives the 3-4-5 polynomial.
    static Segment polynomial(double theta_start, double theta_end, std::vector<double> start, std::vector<double> end,
                              std::vector<std::pair<double, double>> interior = {}) {
        if (!(std::isfinite(theta_start) && std::isfinite(theta_end) && theta_end - theta_start >= min_span))
            detail::fail("polynomial segment: theta_end - theta_start must be finite and at least ", min_span,
                         " rad, got [", theta_start, ", ", theta_end, "] rad");
        auto law = std::make_shared<const LiftPolynomial>(LiftPolynomial::from_conditions(
            theta_start, theta_end, std::move(start), std::move(end), std::move(interior)));
        const double h0 = law->start().front(), h1 = law->end().front();
        return Segment{MotionLaw::from_polynomial(std::move(law)), theta_start, theta_end, h0, h1};
    }

    // The design lift at theta in [theta_start, theta_end] (rad), whatever the law.
    FollowerMotion lift_at(double theta) const {
        if (!(theta >= theta_start - angle_tolerance && theta <= theta_end + angle_tolerance))
            detail::fail("theta = ", theta, " rad is outside the segment [", theta_start, ", ", theta_end, "] rad");
        if (!law.is_custom()) {  // the built-in fast path: a normalized law scaled by the segment
            const double beta = span(), dh = lift();
            const LawValue v = law.evaluate((theta - theta_start) / beta);
            return {h_start + dh * v.S, dh * v.V / beta, dh * v.A / (beta * beta), dh * v.J / (beta * beta * beta)};
        }
        FollowerMotion m = law.evaluate_lift(theta - theta_start);
        m.h += h_start;
        return m;
    }
};

class MotionProgram {
public:
    // Boundaries may be off by up to this much (rad) and are then snapped to exact tiling.
    static constexpr double angle_tolerance = Segment::angle_tolerance;
    // The shortest segment (Segment::min_span), checked again after snapping.
    static constexpr double min_span = Segment::min_span;

    explicit MotionProgram(std::vector<Segment> segments) : segments_(std::move(segments)) { validate(); }

    // Paper Table 1: dwell 0-30 deg, modified-trapezoid rise 30-180 deg by `total_rise` (default
    // 10 mm), dwell 180-210 deg, modified-trapezoid return 210-360 deg.
    // A whole revolution from a lift table, as one periodic B-spline segment (lift_spline.hpp): theta
    // strictly increasing in [0, 2 pi) (rad), h (m). The table is NOT closed: the spline joins the last
    // point to the first one revolution later. A repeated first point at theta[0] + 2 pi with the same h
    // is accepted and dropped; one with another h is refused.
    static MotionProgram from_table(std::vector<double> theta, std::vector<double> h,
                                    const SplineOptions& options = {}) {
        auto spline = std::make_shared<const LiftSpline>(LiftSpline::periodic(std::move(theta), std::move(h), options));
        const double h0 = spline->evaluate(0.0).h;
        return MotionProgram({Segment{MotionLaw::from_spline(std::move(spline)), 0.0, two_pi, h0, h0}});
    }

    static MotionProgram paper_default(double total_rise = 0.010) {
        detail::require_positive(total_rise, "total_rise", "(m)");
        const auto deg = degrees_to_radians;
        const MotionLaw mt = MotionLaw::modified_trapezoid();
        return MotionProgram({{MotionLaw::dwell(), 0.0, deg(30), 0.0, 0.0},
                              {mt, deg(30), deg(180), 0.0, total_rise},
                              {MotionLaw::dwell(), deg(180), deg(210), total_rise, total_rise},
                              {mt, deg(210), two_pi, total_rise, 0.0}});
    }

    const std::vector<Segment>& segments() const { return segments_; }

    // Index of the segment containing theta (any real theta, wrapped to [0, 2 pi)).
    std::size_t segment_index(double theta) const {
        const double t = wrap(theta);
        const auto it = std::upper_bound(segments_.begin(), segments_.end(), t,
                                         [](double v, const Segment& s) { return v < s.theta_start; });
        return static_cast<std::size_t>(it - segments_.begin()) - 1;
    }

    FollowerMotion evaluate(double theta) const {
        if (!std::isfinite(theta)) detail::fail("theta must be finite, got ", theta);
        const double t = wrap(theta);
        FollowerMotion m = segments_[segment_index(t)].lift_at(t);
        if (error_) {
            const LiftError e = error_->evaluate(t);
            m.h += e.e, m.dh += e.de, m.d2h += e.d2e, m.d3h += e.d3e;
        }
        return m;
    }

    // A copy whose lift carries the cam's manufacturing error e(theta), replacing any error this
    // program carries (combine errors with ProfileError::operator+). An empty error gives the design
    // program back.
    MotionProgram with_profile_error(ProfileError error) const {
        MotionProgram copy = *this;
        if (error.empty()) {
            copy.error_.reset();
            copy.max_lift_ = design_max_lift(), copy.min_lift_ = design_min_lift();
            return copy;
        }
        copy.error_ = std::make_shared<const ProfileError>(std::move(error));
        // Sampled over the smooth pieces (breakpoints, sampling_step), then refined.
        const std::vector<double> breaks = copy.breakpoints();
        const double step = copy.sampling_step();
        const auto lift = [&](double t) { return copy.evaluate(t).h; };
        const auto drop = [&](double t) { return -copy.evaluate(t).h; };
        copy.max_lift_ = detail::maximize_piecewise(lift, breaks, 600, step).value;
        copy.min_lift_ = -detail::maximize_piecewise(drop, breaks, 600, step).value;
        return copy;
    }

    // The conjugate program total - h(theta) (the return cam of a conjugate pair: its lift falls where
    // this one rises), from the design lift: a profile error belongs to one cam and is not carried
    // over. Segments of built-in laws only (each keeps its law between mirrored levels); a spline or
    // polynomial segment is refused (give the return program yourself: ConjugateCams checks it).
    MotionProgram complement(double total) const {
        if (!(std::abs(total) <= detail::max_part_length))
            detail::fail("complement: total must be in [", -detail::max_part_length, ", ", detail::max_part_length,
                         "], got ", total);
        std::vector<Segment> mirrored = segments_;
        for (std::size_t i = 0; i < mirrored.size(); ++i) {
            Segment& s = mirrored[i];
            if (s.law.is_custom())
                detail::fail("complement: segments[", i, "] is a ", s.law.name(),
                             " segment; only built-in laws are mirrored (give the conjugate program as its own "
                             "table or segments)");
            s.h_start = total - s.h_start, s.h_end = total - s.h_end;
        }
        return MotionProgram(std::move(mirrored));
    }

    // The manufacturing error the lift carries; nullptr for a design program.
    const ProfileError* profile_error() const { return error_.get(); }

    // Extremes of the lift over the revolution, error included (m).
    double max_lift() const { return max_lift_; }
    double min_lift() const { return min_lift_; }

    // Angles (rad, ascending, 0 first, 2 pi last) between which the lift is smooth and sampling finds
    // everything: segment boundaries and the profile error's features (dent centres and edges).
    std::vector<double> breakpoints() const {
        std::vector<double> out;
        for (const Segment& s : segments_) out.push_back(s.theta_start);
        out.push_back(two_pi);
        if (!error_) return out;
        for (double f : error_->features()) {  // skip one that (nearly) sits on a break already there
            const auto it = std::lower_bound(out.begin(), out.end(), f);
            if ((it != out.end() && *it - f <= angle_tolerance) || (it != out.begin() && f - it[-1] <= angle_tolerance))
                continue;
            out.insert(it, f);
        }
        return out;
    }

    // Largest sampling step (rad) that resolves the profile error and the pieces of any spline segment
    // (a quarter of its shortest piece); +inf for a design program of built-in laws and polynomials.
    double sampling_step() const {
        double step = error_ ? error_->sampling_step() : std::numeric_limits<double>::infinity();
        for (const Segment& s : segments_)
            if (const LiftSpline* spline = s.law.spline()) {
                const std::vector<double>& b = spline->breaks();
                for (std::size_t i = 0; i + 1 < b.size(); ++i) step = std::min(step, 0.25 * (b[i + 1] - b[i]));
            }
        return step;
    }

    // The jumps of the design lift h, h', h'', h''' at every segment boundary, the wrap at 2 pi included
    // (the profile error, smooth across them, is left out). A jump in h^(k) counts when it exceeds
    // 1e-6 of the scale max(stroke / beta_min^k, |left|, |right|) (stroke: max - min lift, beta_min: the
    // shortest segment).
    ContinuityReport continuity() const {
        double beta_min = two_pi;
        for (const Segment& s : segments_) beta_min = std::min(beta_min, s.span());
        const double stroke = design_max_lift() - design_min_lift();
        ContinuityReport report;
        for (std::size_t i = 0; i < segments_.size(); ++i) {
            const std::size_t next = (i + 1) % segments_.size();
            const Segment &a = segments_[i], &b = segments_[next];
            const FollowerMotion l = a.lift_at(a.theta_end), r = b.lift_at(b.theta_start);
            BoundaryContinuity c;
            c.left_segment = i, c.right_segment = next;
            c.theta = next == 0 ? 0.0 : b.theta_start;
            c.left = {l.h, l.dh, l.d2h, l.d3h};
            c.right = {r.h, r.dh, r.d2h, r.d3h};
            c.continuous_through = 3;
            for (int k = 3; k >= 0; --k) {
                const std::size_t q = static_cast<std::size_t>(k);
                c.jump[q] = c.right[q] - c.left[q];
                const double scale =
                    std::max({stroke / std::pow(beta_min, k), std::abs(c.left[q]), std::abs(c.right[q])});
                c.tolerance[q] = 1e-6 * scale;
                if (!(std::abs(c.jump[q]) <= c.tolerance[q])) c.continuous_through = k - 1;
            }
            report.boundaries.push_back(c);
        }
        return report;
    }

    // Throws std::invalid_argument naming the first boundary (segments, angle in degrees) where one of
    // h .. h^(order) jumps. order in [0, 3]: 0 the lift, 1 velocity, 2 acceleration, 3 jerk.
    void require_continuity(int order) const {
        if (order < 0 || order > 3) detail::fail("order must be in [0, 3] (0: h, 1: h', 2: h'', 3: h'''), got ", order);
        for (const BoundaryContinuity& b : continuity().boundaries) {
            if (b.continuous_through >= order) continue;
            const std::size_t k = static_cast<std::size_t>(b.continuous_through + 1);
            detail::fail("require_continuity(", order, "): at the boundary between segments[", b.left_segment, "] (",
                         segments_[b.left_segment].law.name(), ") and segments[", b.right_segment, "] (",
                         segments_[b.right_segment].law.name(), ") at ",
                         b.right_segment == 0 ? "360 deg (the wrap to 0 deg)"
                                              : detail::concat(radians_to_degrees(b.theta), " deg"),
                         ", ", detail::derivative_name(static_cast<int>(k)), " jumps by ", b.jump[k], " (from ",
                         b.left[k], " to ", b.right[k], "); the lift is continuous there only through order ",
                         b.continuous_through);
        }
    }

    static double wrap(double theta) {
        // The first two turns without fmod (a library call per evaluation): theta - 2 pi is exact there
        // (Sterbenz), so the result is fmod's bit for bit.
        if (theta >= 0.0 && theta < two_pi) return theta;
        if (theta >= two_pi && theta < 2.0 * two_pi) return theta - two_pi;
        double t = std::fmod(theta, two_pi);
        if (t < 0.0) t += two_pi;
        return t >= two_pi ? 0.0 : t;
    }

private:
    void validate() {
        if (segments_.empty()) detail::fail("segments must hold at least one segment");
        const double h_scale = 1e-12 + 1e-9 * [&] {
            double m = 0.0;
            for (const Segment& s : segments_) m = std::max({m, std::abs(s.h_start), std::abs(s.h_end)});
            return std::isfinite(m) ? m : 0.0;
        }();
        for (std::size_t i = 0; i < segments_.size(); ++i) {
            const Segment& s = segments_[i];
            const std::string at = detail::concat("segments[", i, "]");
            s.validate(at, h_scale);
            const double expected_start = i == 0 ? 0.0 : segments_[i - 1].theta_end;
            const double gap = s.theta_start - expected_start;
            if (std::abs(gap) > angle_tolerance)
                detail::fail(at, ".theta_start = ", radians_to_degrees(s.theta_start), " deg: ",
                             i == 0 ? "the program must start at 0 deg"
                                    : (gap > 0 ? "leaves a gap after the previous segment, which ends at "
                                               : "overlaps the previous segment, which ends at "),
                             i == 0 ? "" : detail::concat(radians_to_degrees(expected_start), " deg"),
                             "; segments must tile [0, 360) deg exactly");
            if (i > 0 && std::abs(s.h_start - segments_[i - 1].h_end) > h_scale)
                detail::fail(at, ".h_start = ", s.h_start,
                             " m must equal the previous segment's h_end = ", segments_[i - 1].h_end,
                             " m (levels must chain)");
        }
        const Segment& last = segments_.back();
        if (std::abs(last.theta_end - two_pi) > angle_tolerance)
            detail::fail("segments[", segments_.size() - 1, "].theta_end = ", radians_to_degrees(last.theta_end),
                         " deg: the last segment must end at 360 deg (segments must tile [0, 360) deg)");
        if (std::abs(last.h_end - segments_.front().h_start) > h_scale)
            detail::fail("the last segment's h_end = ", last.h_end,
                         " m must equal the first segment's h_start = ", segments_.front().h_start,
                         " m (the program must close over one revolution)");
        // Snap to exact tiling so evaluation at a boundary is unambiguous.
        segments_.front().theta_start = 0.0;
        for (std::size_t i = 1; i < segments_.size(); ++i) {
            segments_[i].theta_start = segments_[i - 1].theta_end;
            segments_[i].h_start = segments_[i - 1].h_end;
        }
        segments_.back().theta_end = two_pi;
        segments_.back().h_end = segments_.front().h_start;
        for (std::size_t i = 0; i < segments_.size(); ++i)
            if (!(segments_[i].span() >= min_span))
                detail::fail(
                    "segments[", i, "] spans ", radians_to_degrees(segments_[i].span()),
                    " deg once the boundaries are snapped to tile the revolution; a segment must span at least ",
                    min_span, " rad (", radians_to_degrees(min_span), " deg)");
        max_lift_ = design_max_lift(), min_lift_ = design_min_lift();
    }

    // Built-in laws stay between their end levels; a custom lift may overshoot them.
    double design_max_lift() const {
        double m = segments_.front().h_start;
        for (const Segment& s : segments_) m = std::max({m, s.h_start, s.h_end, s.h_start + custom_range(s).second});
        return m;
    }
    double design_min_lift() const {
        double m = segments_.front().h_start;
        for (const Segment& s : segments_) m = std::min({m, s.h_start, s.h_end, s.h_start + custom_range(s).first});
        return m;
    }
    static std::pair<double, double> custom_range(const Segment& s) {
        if (const LiftSpline* spline = s.law.spline()) return spline->relative_range();
        if (const LiftPolynomial* polynomial = s.law.polynomial()) return polynomial->relative_range();
        return {0.0, 0.0};
    }

    std::vector<Segment> segments_;
    std::shared_ptr<const ProfileError> error_;  // null: design lift; shared, so copies stay cheap
    double max_lift_ = 0.0, min_lift_ = 0.0;
};

}  // namespace camfollower
