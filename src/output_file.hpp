// SPDX-License-Identifier: BSD-3-Clause
// The command line's output files: every recorded channel as CSV, written atomically, never over the
// config it came from.
#pragma once

#include <sys/stat.h>

#include <cstdio>
#include <string>

#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/solver/observers.hpp"

namespace camfollower::cli {

// Refuse an output path that is the config file itself (same file, by device and inode).
inline void refuse_overwriting(const std::string& output, const std::string& config) {
    struct stat a {}, b {};
    if (::stat(output.c_str(), &a) == 0 && ::stat(config.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino)
        detail::fail("output: '", output, "' is the config file itself; choose another output file");
}

// Header: the channel names with their units; rows: one per recorded step.
inline void write_recording_csv(const std::string& path, const Recording& r, const std::string& config) {
    refuse_overwriting(path, config);
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
    detail::write_file_atomically(path, text, "output");
}

}  // namespace camfollower::cli
