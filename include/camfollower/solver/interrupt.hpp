// SPDX-License-Identifier: BSD-3-Clause
// Cancellation inside one output interval. The driver asks its observer between output steps; an
// adaptive method may take any number of integration steps within one (a tiny max_step, a stiff
// stretch), so those steppers also poll a keep-going callback every `every` integration steps and
// throw Interrupted when it says stop; simulate() ends the run there as cancelled.
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <utility>

namespace camfollower {

struct Interrupted : std::exception {
    const char* what() const noexcept override { return "the run was cancelled within an output interval"; }
};

class InterruptPoll {
public:
    static constexpr std::uint32_t every = 256;  // integration steps between polls (~0.1 ms of work or more)

    void set(std::function<bool()> keep_going) { keep_going_ = std::move(keep_going); }
    // Call once per integration step.
    void operator()() {
        if (keep_going_ && ++count_ % every == 0 && !keep_going_()) throw Interrupted();
    }

private:
    std::function<bool()> keep_going_;
    std::uint32_t count_ = 0;
};

}  // namespace camfollower
