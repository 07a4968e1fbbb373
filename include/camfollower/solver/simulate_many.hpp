// SPDX-License-Identifier: BSD-3-Clause
// Many runs at once: the cases of a study (one system each, same solver settings) spread over a pool
// of threads. Systems are immutable and every run keeps its state in its own workspace, so cases share
// nothing but their (read-only) systems. A case that fails keeps its exception; the others go on.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <optional>
#include <thread>
#include <vector>

#include "camfollower/error.hpp"
#include "camfollower/solver/simulate.hpp"

namespace camfollower {

// Most threads a call may ask for (a typo like 1e6 threads is refused, not attempted).
inline constexpr unsigned max_threads = 1024;

// The number of worker threads for `requested` (0: one per hardware thread) and `count` cases.
inline unsigned worker_threads(unsigned requested, std::size_t count) {
    if (requested > max_threads)
        detail::fail("threads must be in [0, ", max_threads, "] (0: one per hardware thread), got ", requested);
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const unsigned wanted = requested == 0 ? hardware : requested;
    return unsigned(std::max<std::size_t>(1, std::min<std::size_t>(wanted, count)));
}

// job(i) for every i in [0, count) on worker_threads(threads, count) threads, the calling thread
// included; cases are handed out in order as threads become free. `job` must not throw (catch inside).
template <class Job>
void parallel_for(std::size_t count, unsigned threads, Job&& job) {
    const unsigned workers = worker_threads(threads, count);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) job(i);
    };
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    try {
        for (unsigned k = 1; k < workers; ++k) pool.emplace_back(work);
    } catch (...) {  // the system refused a thread: finish on the ones we have
    }
    work();
    for (std::thread& t : pool) t.join();
}

template <class System>
struct CaseRun {
    std::optional<RunResult<System>> result;  // empty when the case failed
    std::exception_ptr error;  // what it threw (ValueError-like std::invalid_argument, ConvergenceError, ...)
    bool ok() const { return result.has_value(); }
};

// simulate() for every system with the same settings; options[i] for case i (one entry: for all).
// threads = 0: one per hardware thread. Results in the systems' order.
template <class System>
std::vector<CaseRun<System>> simulate_many(const std::vector<const System*>& systems, const SolverSettings& settings,
                                           const std::vector<RunOptions>& options, unsigned threads = 0) {
    if (options.size() != 1 && options.size() != systems.size())
        detail::fail("simulate_many: options must hold one entry or one per system (", systems.size(), "), got ",
                     options.size());
    for (std::size_t i = 0; i < systems.size(); ++i)
        if (systems[i] == nullptr) detail::fail("simulate_many: system ", i, " is null");
    settings.validate();
    (void)worker_threads(threads, systems.size());  // refuses a bad thread count before anything runs
    std::vector<CaseRun<System>> runs(systems.size());
    parallel_for(systems.size(), threads, [&](std::size_t i) {
        try {
            runs[i].result.emplace(simulate(*systems[i], settings, options.size() == 1 ? options[0] : options[i]));
        } catch (...) {
            runs[i].error = std::current_exception();
        }
    });
    return runs;
}

}  // namespace camfollower
