// SPDX-License-Identifier: BSD-3-Clause
// Observers for the integrate driver: a recorder of named channels (decimation, recording window,
// memory bound) and the composition with progress reporting and cancellation used by simulate().
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

struct RecordOptions {
    std::size_t decimation = 1;                                   // one row every `decimation` steps
    double from_time = -std::numeric_limits<double>::infinity();  // s: record only from here on (a window)
    double max_bytes = 4.0 * 1024 * 1024 * 1024;                  // refuse runs that would store more

    void validate() const {
        if (decimation < 1) detail::fail("decimation must be >= 1, got ", decimation);
        if (std::isnan(from_time)) detail::fail("record_from must be a time in s, got NaN");
        detail::require_positive(max_bytes, "max_output_bytes");
    }
};

// Recorded time histories: channel-major (each channel contiguous), `rows` filled of `capacity`.
// Channels: "t", "q.<dof>", "v.<dof>", "a.<dof>" for every DOF, then the system's own channels.
struct Recording {
    std::vector<std::string> names;
    std::vector<std::string> dofs;
    std::size_t rows = 0, capacity = 0;
    std::vector<double> data;

    std::size_t index(const std::string& name) const {
        for (std::size_t c = 0; c < names.size(); ++c)
            if (names[c] == name) return c;
        std::string known;
        for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
        detail::fail("unknown channel '", name, "'; recorded channels: ", known);
    }
    const double* channel(std::size_t c) const { return data.data() + c * capacity; }
    const double* channel(const std::string& name) const { return channel(index(name)); }
    double at(const std::string& name, std::size_t row) const { return channel(name)[row]; }
    // First column of the q, v or a block (which = 0, 1, 2); DOF k follows at +k channels.
    std::size_t block(int which) const { return 1 + std::size_t(which) * dofs.size(); }
};

template <class System>
class Recorder {
public:
    Recorder(const System& system, const RecordOptions& options, std::uint64_t planned_steps, double t0, double dt)
        : system_(system), decimation_(options.decimation) {
        options.validate();
        out_.dofs = dof_names(system);
        const std::size_t n = out_.dofs.size();
        out_.names.push_back("t");
        for (const char* prefix : {"q.", "v.", "a."})
            for (const std::string& d : out_.dofs) out_.names.push_back(prefix + d);
        extra_ = channel_names(system);
        for (const std::string& c : extra_) out_.names.push_back(c);
        row_.resize(extra_.size());
        // Rows are taken at step indices that are multiples of the decimation, from the window on.
        for (std::size_t a = 0; a < out_.names.size(); ++a)
            for (std::size_t b = a + 1; b < out_.names.size(); ++b)
                if (out_.names[a] == out_.names[b])
                    detail::fail(
                        "two recorded channels are both named '", out_.names[a],
                        "': rename a DOF or a contact (channels: t, q.<dof>, v.<dof>, a.<dof>, then the system's)");
        // From the window's start on (+inf: nothing), on multiples of the decimation.
        const double first = options.from_time == -std::numeric_limits<double>::infinity()
                                 ? 0.0
                                 : std::ceil((options.from_time - t0) / dt - 1e-9);
        const bool none = first > double(planned_steps);
        first_step_ = none ? planned_steps + 1 : first <= 0.0 ? 0 : static_cast<std::uint64_t>(first);
        first_step_ = (first_step_ + decimation_ - 1) / decimation_ * decimation_;
        const std::uint64_t rows =
            none || first_step_ > planned_steps ? 0 : (planned_steps - first_step_) / decimation_ + 1;
        // A run that records nothing (or one row, nothing to draw) was asked wrongly: say so now, by the
        // option's name, rather than hand back an empty table.
        if (planned_steps > 0 && rows == 0)
            detail::fail("record_from = ", options.from_time,
                         " s: the recording window starts after the run ends (t = ", t0 + double(planned_steps) * dt,
                         " s); nothing would be recorded");
        if (planned_steps > 0 && rows == 1)
            detail::fail("decimation = ", decimation_, " steps with the recording window from step ", first_step_,
                         " of ", planned_steps,
                         " leaves a single row to record; lower decimation or record a longer window");
        const double bytes = double(rows) * 8.0 * double(out_.names.size());
        if (bytes > options.max_bytes)
            detail::fail(planned_steps, " steps at decimation ", decimation_, " would store ", rows, " rows of ",
                         out_.names.size(), " channels (", bytes / 1073741824.0,
                         " GiB) > max_output_bytes = ", options.max_bytes / 1073741824.0,
                         " GiB; increase decimation, record a shorter window "
                         "or shorten the run");
        out_.capacity = std::size_t(rows);
        out_.data.assign(out_.capacity * out_.names.size(), 0.0);
        (void)n;
    }

    // Observer: record state `step` if it falls on the grid (never allocates).
    bool operator()(const State<System>& s, std::uint64_t step) {
        if (step < first_step_ || step % decimation_ != 0 || out_.rows >= out_.capacity) return true;
        const std::size_t n = out_.dofs.size(), cap = out_.capacity, r = out_.rows;
        double* d = out_.data.data();
        d[r] = s.t;
        for (std::size_t k = 0; k < n; ++k) {
            d[(1 + k) * cap + r] = s.q[Eigen::Index(k)];
            d[(1 + n + k) * cap + r] = s.v[Eigen::Index(k)];
            d[(1 + 2 * n + k) * cap + r] = s.a[Eigen::Index(k)];
        }
        if (!extra_.empty()) {
            observe(system_, s.workspace, s.q, s.v, row_.data());
            for (std::size_t c = 0; c < extra_.size(); ++c) d[(1 + 3 * n + c) * cap + r] = row_[c];
        }
        ++out_.rows;
        return true;
    }

    const Recording& recording() const { return out_; }
    Recording take() { return std::move(out_); }

private:
    const System& system_;
    std::size_t decimation_;
    std::uint64_t first_step_ = 0;
    std::vector<std::string> extra_;
    std::vector<double> row_;
    Recording out_;
};

}  // namespace camfollower
