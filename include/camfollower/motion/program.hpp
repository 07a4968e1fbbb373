// A cam motion program: segments that tile one revolution, giving the follower lift h(theta) and its
// derivatives with respect to the cam angle (m, m/rad, m/rad^2, m/rad^3). Periodic in theta.
// The program may carry the cam's manufacturing error (profile_error.hpp), added to the design lift.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "camfollower/detail/extremum.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/motion/profile_error.hpp"

namespace camfollower {

inline constexpr double two_pi = 2.0 * pi;
inline double degrees_to_radians(double deg) { return deg * pi / 180.0; }
inline double radians_to_degrees(double rad) { return rad * 180.0 / pi; }

struct Segment {
    MotionLaw law;
    double theta_start;  // rad
    double theta_end;    // rad
    double h_start;      // m, lift at theta_start
    double h_end;        // m, lift at theta_end

    double span() const { return theta_end - theta_start; }
    double lift() const { return h_end - h_start; }
};

// Lift and its cam-angle derivatives at one theta.
struct FollowerMotion {
    double h;    // m
    double dh;   // m/rad
    double d2h;  // m/rad^2
    double d3h;  // m/rad^3
};

class MotionProgram {
public:
    // Boundaries may be off by up to this much (rad) and are then snapped to exact tiling.
    static constexpr double angle_tolerance = 1e-9;

    explicit MotionProgram(std::vector<Segment> segments) : segments_(std::move(segments)) {
        validate();
    }

    // Paper Table 1: dwell 0-30 deg, modified-trapezoid rise 30-180 deg by `total_rise` (default
    // 10 mm), dwell 180-210 deg, modified-trapezoid return 210-360 deg.
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
        const Segment& s = segments_[segment_index(t)];
        const double beta = s.span(), dh = s.lift();
        const LawValue v = s.law.evaluate((t - s.theta_start) / beta);
        FollowerMotion m{s.h_start + dh * v.S, dh * v.V / beta, dh * v.A / (beta * beta),
                         dh * v.J / (beta * beta * beta)};
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

    // Largest sampling step (rad) that resolves the profile error; +inf for a design program.
    double sampling_step() const {
        return error_ ? error_->sampling_step() : std::numeric_limits<double>::infinity();
    }

    static double wrap(double theta) {
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
            if (!std::isfinite(s.theta_start) || !std::isfinite(s.theta_end))
                detail::fail(at, ".theta_start/theta_end must be finite");
            if (!std::isfinite(s.h_start) || !std::isfinite(s.h_end))
                detail::fail(at, ".h_start/h_end must be finite (m), got ", s.h_start, ", ", s.h_end);
            if (!(s.span() > 0.0))
                detail::fail(at, ": span beta = theta_end - theta_start must be > 0 rad, got ",
                             s.span(), " rad (", radians_to_degrees(s.span()), " deg)");
            if (s.law.is_dwell() && std::abs(s.lift()) > h_scale)
                detail::fail(at, ": a dwell must have h_end == h_start, got a lift of ", s.lift(), " m");
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
                detail::fail(at, ".h_start = ", s.h_start, " m must equal the previous segment's h_end = ",
                             segments_[i - 1].h_end, " m (levels must chain)");
        }
        const Segment& last = segments_.back();
        if (std::abs(last.theta_end - two_pi) > angle_tolerance)
            detail::fail("segments[", segments_.size() - 1, "].theta_end = ",
                         radians_to_degrees(last.theta_end),
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
        max_lift_ = design_max_lift(), min_lift_ = design_min_lift();
    }

    double design_max_lift() const {
        double m = segments_.front().h_start;
        for (const Segment& s : segments_) m = std::max({m, s.h_start, s.h_end});
        return m;
    }
    double design_min_lift() const {
        double m = segments_.front().h_start;
        for (const Segment& s : segments_) m = std::min({m, s.h_start, s.h_end});
        return m;
    }

    std::vector<Segment> segments_;
    std::shared_ptr<const ProfileError> error_;  // null: design lift; shared, so copies stay cheap
    double max_lift_ = 0.0, min_lift_ = 0.0;
};

}  // namespace camfollower
