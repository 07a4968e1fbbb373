// SPDX-License-Identifier: BSD-3-Clause
// Test helper: simulate a system and return its histories row-major (q[n * i + k]), as tests read them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "camfollower/solver/simulate.hpp"
#include "camfollower/precompiled.hpp"  // simulate() for the library's mechanisms, compiled once

template <class System>
struct Histories {
    std::size_t rows = 0;
    std::vector<double> t, q, v, a;
    camfollower::SolverStatistics stats;
    camfollower::Recording recording;
    camfollower::State<System> final_state;

    const double* channel(const std::string& name) const { return recording.channel(name); }
};

template <class System>
Histories<System> run(const System& system, const camfollower::SolverSettings& settings, double duration,
                      std::size_t decimation = 1, double max_bytes = 4.0 * 1024 * 1024 * 1024) {
    camfollower::RunOptions options;
    options.duration = duration;
    options.record.decimation = decimation;
    options.record.max_bytes = max_bytes;
    auto r = camfollower::simulate(system, settings, options);
    Histories<System> h;
    const camfollower::Recording& rec = r.recording;
    const std::size_t n = rec.dofs.size();
    h.rows = rec.rows;
    h.t.assign(rec.channel(0), rec.channel(0) + rec.rows);
    for (auto [which, out] : {std::pair{0, &h.q}, std::pair{1, &h.v}, std::pair{2, &h.a}})
        for (std::size_t i = 0; i < rec.rows; ++i)
            for (std::size_t k = 0; k < n; ++k) out->push_back(rec.channel(rec.block(which) + k)[i]);
    h.stats = r.report.stats;
    h.recording = std::move(r.recording);
    h.final_state = std::move(r.final_state);
    return h;
}
