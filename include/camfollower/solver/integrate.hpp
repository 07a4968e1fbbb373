// SPDX-License-Identifier: BSD-3-Clause
// The integrate driver (odeint's split: stepper / driver / observers): advance a stepper's state to
// t_end in steps of the stepper's size, calling the observer after the start and after every accepted
// step. The observer returns false to stop the run early (cancellation); integrate then returns with
// `cancelled` set and the state at the last accepted step. A stepper may also stop within a step
// (solver/interrupt.hpp: Interrupted), with the same outcome.
#pragma once

#include <cmath>
#include <cstdint>

#include "camfollower/error.hpp"
#include "camfollower/solver/interrupt.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

struct IntegrationReport {
    SolverStatistics stats;
    std::uint64_t planned_steps = 0;
    bool cancelled = false;
};

// Number of steps of size dt that cover `duration` (the last step may end past it by < dt).
inline std::uint64_t steps_for(double duration, double dt) {
    detail::require_positive(duration, "duration", "(s)");
    const double steps = std::ceil(duration / dt - 1e-9);
    // 1e10 steps is about an hour at the paper model's 3-4 million steps/s: a longer run is a typo in
    // the duration or the step far more often than a plan (recorded rows are capped separately).
    if (!(steps <= 1e10))
        detail::fail("duration / time_step = ", steps,
                     " steps is too many (limit 1e10); shorten the duration or "
                     "lengthen the time step");
    return static_cast<std::uint64_t>(std::max(steps, 1.0));
}

// observer(const State&, std::uint64_t step_index) -> bool (continue?); step 0 is the start state.
template <class Stepper, class Observer>
IntegrationReport integrate(Stepper& stepper, typename Stepper::StateType& state, double duration,
                            Observer&& observer) {
    IntegrationReport report;
    report.planned_steps = steps_for(duration, stepper.time_step());
    if (!observer(state, std::uint64_t(0))) {
        report.cancelled = true;
        return report;
    }
    // Time as t0 + n dt, not summed step by step: a sum drifts by ~n ulps (3e-8 s after 4 million
    // steps at t = 80 s), a phase error that keeps exciting lightly damped modes of long runs.
    const double t0 = state.t;
    for (std::uint64_t n = 1; n <= report.planned_steps; ++n) {
        try {
            stepper.step(state, report.stats);
        } catch (const Interrupted&) {  // asked to stop within the interval: the state where it stopped
            report.cancelled = true;
            break;
        }
        state.t = t0 + double(n) * stepper.time_step();
        if (!observer(state, n)) {
            report.cancelled = true;
            break;
        }
    }
    return report;
}

}  // namespace camfollower
