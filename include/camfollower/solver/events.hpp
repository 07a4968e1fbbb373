// SPDX-License-Identifier: BSD-3-Clause
// Events: the instants where a system's switching function (core/system.hpp: event_values, > 0 in
// contact) changes sign — a contact lost or made, a clearance's wall touched or left. There the force
// stops being smooth, and a method of order p keeps its order only if no step straddles the instant.
//
// EventWatch follows the signs from one accepted step to the next. When a step changes a sign it
// locates the crossing on the step's own interpolant (Dormand-Prince's dense output, Newmark's cubic
// Hermite through q and v at both ends) by the Illinois variant of regula falsi, to a small fraction of
// the step. Dormand-Prince then shortens the step to end at the earliest crossing (solver/
// dormand_prince.hpp), so the next step starts on the far side; Newmark's fixed step only reports it.
// The sign test sees crossings that change a sign over one step: a contact that opens and closes again
// within a single step is not reported (with Dormand-Prince, at its error-controlled steps, such a
// flight is also below the tolerance's resolution of the motion).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "camfollower/core/system.hpp"
#include "camfollower/detail/force_inline.hpp"

namespace camfollower {

struct Event {
    double time = 0.0;  // s
    int index = 0;      // into event_names(system)
    int direction = 0;  // +1 the switching function rose through zero (contact made), -1 fell (lost)
};

// A sign change found in a step: the switching function `index` crosses zero at `time`; `beyond` is a
// time past the crossing within the located bracket (where the function is on its new side).
struct Crossing {
    int index = -1;
    double time = std::numeric_limits<double>::infinity();
    double beyond = std::numeric_limits<double>::infinity();
    explicit operator bool() const { return index >= 0; }
};

template <class System>
class EventWatch {
public:
    using Vector = typename System::Vector;

    explicit EventWatch(const System& system)
        : system_(system),
          count_(int(event_names(system).size())),
          g_(std::size_t(count_)),
          g_scan_(std::size_t(count_)),
          side_(std::size_t(count_)),
          scratch_(make_workspace(system)) {
        q_.resize(system.size()), v_.resize(system.size()), f_.resize(system.size());
        events_.reserve(64);
    }

    int count() const { return count_; }
    const std::vector<Event>& events() const { return events_; }
    std::vector<Event> take_events() { return std::move(events_); }

    // Starts watching at an accepted state (the workspace prepared at its time); forgets past events.
    void start(const workspace_t<System>& ws, const Vector& q, const Vector& v) {
        events_.clear();
        if (count_ == 0) return;
        event_values(system_, ws, q, v, g_.data());
        for (std::size_t k = 0; k < g_.size(); ++k) side_[k] = g_[k] > 0.0 ? 1 : -1;
    }

    // After a step from t0 to t1 ending at (q1, v1), `ws` prepared at t1 with force() just evaluated
    // there: whether a switching function changed sign. Cheap: the functions at the new state only.
    CAMFOLLOWER_FORCE_INLINE bool changed(const workspace_t<System>& ws, const Vector& q1, const Vector& v1) {
        if (count_ == 0) return false;
        double* g = g_.data();
        const int* side = side_.data();
        event_values(system_, ws, q1, v1, g);
        bool any = false;  // (no early exit: one predictable loop)
        for (int k = 0; k < count_; ++k) any |= (g[k] > 0.0) != (side[k] > 0);
        return any;
    }

    // The earliest crossing in (t0, t1] of the functions changed() saw change, located on
    // path(t, q, v) (fills q, v at t in [t0, t1]). Call after changed() returned true.
    template <class Path>
    Crossing earliest(double t0, double t1, Path&& path) {
        Crossing first;
        for (std::size_t k = 0; k < g_.size(); ++k) {
            if ((g_[k] > 0.0 ? 1 : -1) == side_[k]) continue;
            const Crossing c = locate(int(k), t0, t1, path);
            if (c.time < first.time) first = c;
        }
        return first;
    }

    // Records the crossing as an event, moves its function to the new side and tells the system
    // (event_located: the step's workspace `ws` keeps the instant in its path memory).
    void record(const Crossing& c, workspace_t<System>& ws) {
        const std::size_t k = std::size_t(c.index);
        side_[k] = -side_[k];
        events_.push_back({c.time, c.index, side_[k]});
        event_located(system_, ws, c.index, c.time, side_[k]);
    }

    // Newmark's path: the cubic Hermite interpolant through (q0, v0) at t0 and (q1, v1) at t1 (third-
    // order accurate in q, like the scheme), its derivative for v.
    static void hermite(double t, double t0, double t1, const Vector& q0, const Vector& v0, const Vector& q1,
                        const Vector& v1, Vector& q, Vector& v) {
        const double h = t1 - t0, s = (t - t0) / h, s2 = s * s, s3 = s2 * s;
        const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
        const double d00 = (6 * s2 - 6 * s) / h, d10 = 3 * s2 - 4 * s + 1, d01 = (-6 * s2 + 6 * s) / h,
                     d11 = 3 * s2 - 2 * s;
        q = h00 * q0 + (h10 * h) * v0 + h01 * q1 + (h11 * h) * v1;
        v = d00 * q0 + d10 * v0 + d01 * q1 + d11 * v1;
    }

private:
    template <class Path>
    double value_at(int k, double t, Path& path) {
        path(t, q_, v_);
        prepare(system_, t, scratch_);
        nonlinear_force(system_, scratch_, q_, v_, f_);  // event_values() follows force() (core/system.hpp)
        event_values(system_, scratch_, q_, v_, g_scan_.data());
        return g_scan_[std::size_t(k)];
    }

    // Illinois: regula falsi with the stale end's value halved, superlinear and always bracketed.
    // The old end's value is taken on its recorded side (a step that started at a located crossing
    // may start a rounding error on the wrong side of zero); evaluated here, on the rare path, so the
    // common one keeps no old values.
    template <class Path>
    Crossing locate(int k, double t0, double t1, Path& path) {
        const int old_side = side_[std::size_t(k)];
        double a = t0, b = t1;
        const double g0 = value_at(k, t0, path);
        double fa = old_side > 0 ? std::max(g0, tiny) : std::min(g0, -tiny);
        double fb = g_[std::size_t(k)];
        const double width = std::max(1e-10 * (t1 - t0), 8.0 * std::numeric_limits<double>::epsilon() * std::abs(t1));
        int last = 0;  // +1: the old-side end moved last, -1: the new-side end
        for (int it = 0; it < 200 && b - a > width; ++it) {
            double t = (a * fb - b * fa) / (fb - fa);
            if (!(t > a && t < b)) t = 0.5 * (a + b);
            const double ft = value_at(k, t, path);
            if ((ft > 0.0 ? 1 : -1) == old_side) {
                a = t, fa = ft;
                if (last == 1) fb *= 0.5;
                last = 1;
            } else {
                b = t, fb = ft;
                if (last == -1) fa *= 0.5;
                last = -1;
            }
        }
        Crossing c;
        c.index = k;
        c.beyond = b;
        c.time = fa == fb ? b : std::clamp((a * fb - b * fa) / (fb - fa), a, b);
        return c;
    }

    static constexpr double tiny = 1e-300;
    const System& system_;
    int count_;
    std::vector<double> g_, g_scan_;
    std::vector<int> side_;
    workspace_t<System> scratch_;  // prepared at the interpolant's times (no path memory needed)
    Vector q_, v_, f_;
    std::vector<Event> events_;
};

}  // namespace camfollower
