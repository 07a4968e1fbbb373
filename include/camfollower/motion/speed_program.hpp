// SPDX-License-Identifier: BSD-3-Clause
// The camshaft's rotation as a function of time: a constant speed, speed ramps (run-up, run-down,
// speed changes) and a periodic modulation (a servo drive's variable speed).
//
// The base speed holds at initial_speed, then each ramp takes it from the speed before it to its
// to_speed over [start, start + duration]:
//   smooth   w = w_a + dw (tau - sin(2 pi tau) / (2 pi)),  w' = dw / T (1 - cos(2 pi tau))  (no step in w')
//   linear   w = w_a + dw tau,                              w' = dw / T                     (steps in w')
// with tau = (t - start) / T. A modulation turns the base angle theta_b into
//   theta = theta_b - (e / k) (cos(k theta_b + phi) - cos phi),   theta' = theta_b' (1 + e sin(k theta_b + phi)),
// k whole: k speed cycles per base revolution, at constant base speed periodic with the revolution.
// Every expression is closed-form, so the cam angle, speed and acceleration are exact at any t.
// The camshaft never turns backwards (speeds >= 0, |e| < 1); it may stand still.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"

namespace camfollower {

enum class RampShape { smooth, linear };
inline const char* ramp_shape_name(RampShape s) { return s == RampShape::smooth ? "smooth" : "linear"; }
inline RampShape ramp_shape_from(const std::string& name) {
    if (name == "smooth") return RampShape::smooth;
    if (name == "linear") return RampShape::linear;
    detail::fail("ramp shape must be 'smooth' or 'linear', got '", name, "'");
}

// A change of the base speed to to_speed (rad/s) over [start, start + duration] (s).
struct SpeedRamp {
    double start = 0.0, duration = 0.0, to_speed = 0.0;
    RampShape shape = RampShape::smooth;
};

// theta' = theta_b' (1 + amplitude sin(harmonic theta_b + phase)): amplitude in (-1, 1), harmonic a
// whole number of speed cycles per base revolution, phase in rad.
struct SpeedModulation {
    double amplitude = 0.0;
    int harmonic = 1;
    double phase = 0.0;
};

// The camshaft's angle (rad), speed (rad/s) and angular acceleration (rad/s^2) at one instant.
struct DriveState {
    double angle, rate, acceleration;
};

class SpeedProgram {
public:
    // Turning at a constant speed (rad/s) from angle 0 at t = 0.
    static SpeedProgram constant(double speed) { return SpeedProgram(speed, {}, std::nullopt); }

    // From initial_speed (rad/s, >= 0) through the ramps, in time order, not overlapping, from t >= 0,
    // with an optional modulation on top. The highest base speed (the nominal speed) must be > 0.
    SpeedProgram(double initial_speed, std::vector<SpeedRamp> ramps, std::optional<SpeedModulation> modulation = {})
        : initial_speed_(initial_speed), ramps_(std::move(ramps)), modulation_(modulation) {
        validate();
        precompute();
    }

    double initial_speed() const { return initial_speed_; }
    const std::vector<SpeedRamp>& ramps() const { return ramps_; }
    const std::optional<SpeedModulation>& modulation() const { return modulation_; }

    // The highest base speed, rad/s: the speed the program is built around (its revolutions, error
    // scales and studies count at it).
    double nominal_speed() const { return nominal_; }
    // Turning at one speed all the time.
    bool is_constant() const { return constant_; }
    // The motion repeats every revolution at the nominal speed (no ramps): a periodic steady state exists.
    bool periodic() const { return ramps_.empty(); }
    // The same program with every base speed scaled so that the nominal speed is `speed` (rad/s).
    SpeedProgram scaled_to(double speed) const {
        detail::require_camshaft_speed(speed, "camshaft speed");
        const double f = speed / nominal_;
        std::vector<SpeedRamp> r = ramps_;
        for (SpeedRamp& x : r) x.to_speed *= f;
        return SpeedProgram(initial_speed_ * f, std::move(r), modulation_);
    }

    DriveState at(double t) const {
        if (constant_) return {nominal_ * t, nominal_, 0.0};
        const DriveState b = base(t);
        if (!modulation_) return b;
        const SpeedModulation& m = *modulation_;
        const double k = m.harmonic, x = k * b.angle + m.phase, s = std::sin(x), c = std::cos(x);
        return {b.angle - m.amplitude / k * (c - cos_phase_), b.rate * (1.0 + m.amplitude * s),
                b.acceleration * (1.0 + m.amplitude * s) + m.amplitude * k * b.rate * b.rate * c};
    }
    double angle(double t) const { return at(t).angle; }
    double rate(double t) const { return at(t).rate; }

    // The first time (s) the camshaft reaches `angle` (rad): angle / speed at constant speed (any
    // sign); otherwise angle >= 0 and reached (a program ending at standstill reaches a last angle).
    double time_at_angle(double angle) const {
        detail::require_finite(angle, "cam angle");
        if (constant_) return angle / nominal_;
        if (angle < 0.0)
            detail::fail("cam angle ", angle, " rad: a variable-speed camshaft starts at angle 0 at t = 0");
        if (angle == 0.0) return 0.0;
        // Bracket: past the last ramp the base speed is constant.
        double hi = ramps_.empty() ? 0.0 : ramps_.back().start + ramps_.back().duration;
        const double final_speed = ramps_.empty() ? initial_speed_ : ramps_.back().to_speed;
        if (this->angle(hi) < angle) {
            if (final_speed == 0.0)
                detail::fail("cam angle ", angle, " rad is never reached: the speed program stops the camshaft at ",
                             this->angle(hi), " rad");
            // The modulation moves the angle by at most 2 |e| / k from the base's.
            const double extra = 2.0 * (modulation_ ? std::abs(modulation_->amplitude) / modulation_->harmonic : 0.0);
            hi += (angle - base(hi).angle + extra) / final_speed + 1e-12;
        }
        double lo = 0.0;
        for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, hi); ++i) {
            const double mid = 0.5 * (lo + hi);
            (this->angle(mid) < angle ? lo : hi) = mid;
        }
        return hi;
    }

private:
    void validate() const {
        const double top = detail::max_camshaft_speed;
        if (!(std::isfinite(initial_speed_) && initial_speed_ >= 0.0 && initial_speed_ <= top))
            detail::fail("speed program: initial speed must be in [0, ", top, "] rad/s, got ", initial_speed_,
                         " rad/s (the camshaft turns forward or stands still)");
        double end = 0.0;
        for (std::size_t i = 0; i < ramps_.size(); ++i) {
            const SpeedRamp& r = ramps_[i];
            const std::string who = "speed program: ramp " + std::to_string(i + 1);
            if (!(std::isfinite(r.start) && r.start >= end))
                detail::fail(
                    who, " starts at ", r.start, " s; ramps run in time order from t = 0 without overlap (",
                    i == 0 ? "start >= 0 s" : "start >= the previous ramp's end, " + std::to_string(end) + " s", ")");
            if (!(std::isfinite(r.duration) && r.duration > 0.0 && r.duration <= 1e6))
                detail::fail(who, " duration must be in (0, 1e6] s, got ", r.duration, " s");
            if (!(std::isfinite(r.to_speed) && r.to_speed >= 0.0 && r.to_speed <= top))
                detail::fail(who, " to_speed must be in [0, ", top, "] rad/s, got ", r.to_speed,
                             " rad/s (the camshaft turns forward or stands still; reversing is not modelled)");
            end = r.start + r.duration;
        }
        double nominal = initial_speed_;
        for (const SpeedRamp& r : ramps_) nominal = std::max(nominal, r.to_speed);
        if (!(nominal >= detail::min_camshaft_speed))
            detail::fail("speed program: the camshaft never turns (its highest speed is ", nominal, " rad/s, at least ",
                         detail::min_camshaft_speed, " rad/s needed)");
        if (modulation_) {
            const SpeedModulation& m = *modulation_;
            if (!(std::isfinite(m.amplitude) && std::abs(m.amplitude) < 1.0))
                detail::fail(
                    "speed program: modulation amplitude must be in (-1, 1) (a fraction of the base speed; at "
                    "+-1 the camshaft would stop or reverse), got ",
                    m.amplitude);
            if (!(m.harmonic >= 1 && m.harmonic <= 1000))
                detail::fail(
                    "speed program: modulation harmonic must be a whole number in [1, 1000] (speed cycles per "
                    "revolution), got ",
                    m.harmonic);
            detail::require_finite(m.phase, "speed program: modulation phase");
        }
    }
    void precompute() {
        nominal_ = initial_speed_;
        for (const SpeedRamp& r : ramps_) nominal_ = std::max(nominal_, r.to_speed);
        constant_ = ramps_.empty() && (!modulation_ || modulation_->amplitude == 0.0);
        cos_phase_ = modulation_ ? std::cos(modulation_->phase) : 1.0;
        // The base angle and speed at each ramp's start.
        double t = 0.0, angle = 0.0, speed = initial_speed_;
        for (const SpeedRamp& r : ramps_) {
            angle += speed * (r.start - t);
            const double start = angle;
            angle += ramp_angle(r, speed, r.duration);
            starts_.push_back({start, speed, angle});
            speed = r.to_speed;
            t = r.start + r.duration;
        }
    }
    // The base angle gained over the first s seconds of ramp r from speed w_a.
    static double ramp_angle(const SpeedRamp& r, double w_a, double s) {
        const double T = r.duration, tau = s / T, dw = r.to_speed - w_a;
        if (r.shape == RampShape::linear) return w_a * s + dw * T * 0.5 * tau * tau;
        return w_a * s + dw * T * (0.5 * tau * tau + (std::cos(two_pi * tau) - 1.0) / (4.0 * pi * pi));
    }
    DriveState base(double t) const {
        // The last ramp starting at or before t (ramps are few).
        std::size_t i = ramps_.size();
        while (i > 0 && ramps_[i - 1].start > t) --i;
        if (i == 0) return {initial_speed_ * t, initial_speed_, 0.0};
        const SpeedRamp& r = ramps_[i - 1];
        const Start& a = starts_[i - 1];
        const double s = t - r.start;
        if (s >= r.duration) return {a.end_angle + r.to_speed * (s - r.duration), r.to_speed, 0.0};
        const double T = r.duration, tau = s / T, dw = r.to_speed - a.speed;
        if (r.shape == RampShape::linear) return {a.angle + ramp_angle(r, a.speed, s), a.speed + dw * tau, dw / T};
        return {a.angle + ramp_angle(r, a.speed, s), a.speed + dw * (tau - std::sin(two_pi * tau) / two_pi),
                dw / T * (1.0 - std::cos(two_pi * tau))};
    }

    struct Start {
        double angle, speed, end_angle;  // base angle and speed at a ramp's start, angle at its end
    };
    double initial_speed_;
    std::vector<SpeedRamp> ramps_;
    std::optional<SpeedModulation> modulation_;
    std::vector<Start> starts_;
    double nominal_ = 0.0, cos_phase_ = 1.0;
    bool constant_ = true;
};

}  // namespace camfollower
