// SPDX-License-Identifier: BSD-3-Clause
// Run a periodically forced system (a camshaft turning at constant speed) revolution by revolution
// until it has settled on its periodic response: the largest change of the watched accelerations
// between two successive revolutions, relative to their largest magnitude in the revolution,
//     change_k = max_j max_i |a_j(t_i + k T) - a_j(t_i + (k - 1) T)| / max_j max_i |a_j(t_i + k T)|,
// falls below a tolerance. A response that never settles (chaos, chatter, an undamped mode) is
// reported as such, with the history, after max_revolutions.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "camfollower/error.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

struct SettleOptions {
    bool enabled = false;
    double period = 0.0;      // s, one revolution; the time step must divide it
    std::vector<int> dofs;    // watched accelerations (empty: every DOF)
    double tolerance = 1e-4;  // relative change per revolution
    int min_revolutions = 2;
    int max_revolutions = 200;

    void validate(int n, double dt) const {
        detail::require_positive(period, "settle period", "(s)");
        if (!(tolerance > 0.0 && tolerance < 1.0)) detail::fail("settle tolerance must be in (0, 1), got ", tolerance);
        if (min_revolutions < 2) detail::fail("settle min_revolutions must be >= 2, got ", min_revolutions);
        if (max_revolutions < min_revolutions)
            detail::fail("settle max_revolutions (", max_revolutions, ") must be >= min_revolutions (", min_revolutions,
                         ")");
        for (int d : dofs)
            if (d < 0 || d >= n) detail::fail("settle DOF index ", d, " is out of range [0, ", n, ")");
        const double steps = std::round(period / dt);
        if (!(steps >= 1.0 && std::abs(steps * dt - period) <= 1e-9 * period))
            detail::fail(
                "to settle revolution by revolution the time step must divide the period: period / time_step = ",
                period / dt, " is not a whole number");
    }
};

struct SettleReport {
    bool requested = false;
    bool settled = false;
    int revolutions = 0;                                                // simulated while settling
    double change = std::numeric_limits<double>::quiet_NaN();           // relative, last revolution
    double change_absolute = std::numeric_limits<double>::quiet_NaN();  // m/s^2 (units of a)
    std::vector<double> history;  // relative change per revolution, from the second on
};

// Advances `state` by whole revolutions; keep_going(steps) is polled every revolution (false cancels).
template <class Stepper, class KeepGoing>
SettleReport settle(Stepper& stepper, typename Stepper::StateType& state, const SettleOptions& options,
                    SolverStatistics& stats, KeepGoing&& keep_going) {
    const int n = int(state.q.size());
    options.validate(n, stepper.time_step());
    std::vector<int> dofs = options.dofs;
    if (dofs.empty())
        for (int j = 0; j < n; ++j) dofs.push_back(j);
    const auto steps = static_cast<std::uint64_t>(std::round(options.period / stepper.time_step()));
    const std::size_t width = dofs.size();
    std::vector<double> previous(steps * width), current(steps * width);
    SettleReport report;
    report.requested = true;
    const double t0 = state.t;  // time as t0 + k dt (integrate.hpp)
    for (int rev = 1; rev <= options.max_revolutions; ++rev) {
        double largest = 0.0, change = 0.0;
        for (std::uint64_t i = 0; i < steps; ++i) {
            stepper.step(state, stats);
            state.t = t0 + double((std::uint64_t(rev) - 1) * steps + i + 1) * stepper.time_step();
            for (std::size_t j = 0; j < width; ++j) {
                const double a = state.a[dofs[j]];
                double& slot = current[i * width + j];
                slot = a;
                largest = std::max(largest, std::abs(a));
                if (rev > 1) change = std::max(change, std::abs(a - previous[i * width + j]));
            }
        }
        report.revolutions = rev;
        if (rev > 1) {
            report.change_absolute = change;
            report.change = largest > 0.0 ? change / largest : 0.0;
            report.history.push_back(report.change);
            if (rev >= options.min_revolutions && report.change <= options.tolerance) {
                report.settled = true;
                break;
            }
        }
        std::swap(previous, current);
        if (!keep_going(std::uint64_t(rev) * steps)) break;
    }
    return report;
}

}  // namespace camfollower
