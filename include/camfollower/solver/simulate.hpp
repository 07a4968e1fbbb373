// One call for the common case: start a system in its initial state (or a given
// state), integrate with Newmark/HHT for a duration, record named channels, report progress and
// honour cancellation.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "camfollower/solver/integrate.hpp"
#include "camfollower/solver/newmark.hpp"
#include "camfollower/solver/observers.hpp"

namespace camfollower {

struct RunOptions {
    double duration = 0.0;  // s
    RecordOptions record;
    // Called every `progress_every` steps with (steps done, steps planned); return false to cancel.
    std::function<bool(std::uint64_t, std::uint64_t)> progress;
    std::uint64_t progress_every = 100000;
};

template <class System>
struct RunResult {
    Recording recording;
    IntegrationReport report;
    State<System> final_state;
    double time_step = 0.0;
    std::size_t decimation = 1;
};

template <class System>
RunResult<System> simulate(const System& system, const NewmarkSettings& settings, const RunOptions& options,
                           const std::optional<typename System::Vector>& q0 = std::nullopt,
                           const std::optional<typename System::Vector>& v0 = std::nullopt) {
    using Vector = typename System::Vector;
    if (options.progress && options.progress_every < 1) detail::fail("progress_every must be >= 1");
    Newmark<System> stepper(system, settings);
    const std::uint64_t steps = steps_for(options.duration, settings.time_step);
    const Vector q = q0 ? *q0 : initial_displacement(system);
    const Vector v = v0 ? *v0 : initial_velocity(system);
    RunResult<System> result;
    result.final_state = stepper.start(0.0, q, v);
    Recorder<System> recorder(system, options.record, steps, 0.0, settings.time_step);
    const std::uint64_t every = options.progress ? options.progress_every : 0;
    result.report = integrate(stepper, result.final_state, options.duration,
                              [&](const State<System>& s, std::uint64_t n) {
                                  recorder(s, n);
                                  if (every && n % every == 0 && n > 0) return options.progress(n, steps);
                                  return true;
                              });
    result.recording = recorder.take();
    result.time_step = settings.time_step;
    result.decimation = options.record.decimation;
    return result;
}

}  // namespace camfollower
