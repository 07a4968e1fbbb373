// SPDX-License-Identifier: BSD-3-Clause
// A test problem with events and a closed form: a mass bouncing on a linear unilateral spring.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "camfollower/constants.hpp"
#include "camfollower/core/system.hpp"

// A mass m dropped from height h0 at rest onto a linear spring k (no damping, gravity g): flight,
// contact while x < 0 (force k (-x), a kink in the force at x = 0), flight again. Closed form:
// contact at t1 = sqrt(2 h0 / g) with speed v1 = g t1; in contact x = -d + d cos(w s) - (v1 / w)
// sin(w s), d = m g / k, w = sqrt(k / m), leaving at s = (2 pi - 2 phi) / w, tan phi = v1 / (w d),
// with speed v1; the flight back lasts 2 v1 / g; and so on, periodically.
// with_events = false: the same system without its switching function (one type for both, so that
// simulate() is compiled once for it).
struct Bouncer {
    using Vector = Eigen::Matrix<double, 1, 1>;
    using Matrix = Eigen::Matrix<double, 1, 1>;
    struct Workspace {};
    double m = 0.5, k = 2.0e5, g = 9.81, h0 = 0.02;
    bool with_events = true;
    Matrix M = Matrix::Constant(0.5), zero = Matrix::Zero();

    int size() const { return 1; }
    const Matrix& mass() const { return M; }
    const Matrix& damping() const { return zero; }
    const Matrix& stiffness() const { return zero; }
    Vector initial_displacement() const { return Vector::Constant(h0); }
    Workspace workspace() const { return {}; }
    void prepare(double, Workspace&) const {}
    // f - p with p = -m g (gravity) and the spring's internal force -k (-x) when x < 0.
    void force(const Workspace&, const Vector& q, const Vector&, Vector& f) const {
        f[0] = m * g - (q[0] < 0.0 ? k * -q[0] : 0.0);
    }
    int max_rank() const { return 1; }
    void tangent(const Workspace&, const Vector& q, const Vector&, double cq, double,
                 camfollower::LowRank<Vector>& uv) const {
        if (q[0] < 0.0) uv.add(Vector::Ones(), Vector::Constant(cq * k));
    }
    std::vector<std::string> event_names() const {
        if (with_events) return {"ground"};
        return {};
    }
    void event_values(const Workspace&, const Vector& q, const Vector&, double* out) const {
        if (with_events) out[0] = -q[0];
    }

    double flight() const { return 2.0 * std::sqrt(2.0 * h0 / g); }  // between two contacts
    double impact_speed() const { return std::sqrt(2.0 * g * h0); }
    double contact_time() const {
        const double w = std::sqrt(k / m), d = m * g / k;
        return (2.0 * camfollower::pi - 2.0 * std::atan(impact_speed() / (w * d))) / w;
    }
    // Exact event times (made, lost, made, ...) up to t_end.
    std::vector<double> event_times(double t_end) const {
        std::vector<double> out;
        double t = 0.5 * flight();
        for (int i = 0; t <= t_end; ++i) {
            out.push_back(t);
            t += i % 2 == 0 ? contact_time() : flight();
        }
        return out;
    }
    // Exact height at t.
    double height(double t) const {
        const double v1 = impact_speed(), w = std::sqrt(k / m), d = m * g / k;
        const double period = flight() + contact_time();
        double s = std::fmod(t + 0.5 * flight(), period);  // time since the last lift-off (or start - t1)
        if (s < flight()) return v1 * s - 0.5 * g * s * s;
        s -= flight();
        return -d + d * std::cos(w * s) - (v1 / w) * std::sin(w * s);
    }
};
