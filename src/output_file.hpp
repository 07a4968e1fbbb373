// SPDX-License-Identifier: BSD-3-Clause
// The command line's output files: every recorded channel as CSV, written atomically, never over the
// config it came from.
#pragma once

#include <cstdio>
#include <string>

#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/solver/observers.hpp"

namespace camfollower::cli {

// Header: the channel names with their units; rows: one per recorded step.
inline void write_recording_csv(const std::string& path, const Recording& r, const std::string& config) {
    std::string text;
    text.reserve(r.rows * r.names.size() * 20 + 256);
    for (std::size_t c = 0; c < r.names.size(); ++c) text += (c ? "," : "") + r.names[c];
    text += '\n';
    char number[32];
    for (std::size_t i = 0; i < r.rows; ++i) {
        for (std::size_t c = 0; c < r.names.size(); ++c) {
            const int n = std::snprintf(number, sizeof number, c ? ",%.12g" : "%.12g", r.channel(c)[i]);
            text.append(number, std::size_t(n));
        }
        text += '\n';
    }
    detail::write_file_atomically(path, text, "output", {config});
}

}  // namespace camfollower::cli
