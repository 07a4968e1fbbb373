// SPDX-License-Identifier: BSD-3-Clause
// Continuity of a motion program across its segment boundaries: the jumps of h, h', h'', h''' at each
// boundary (the wrap at 2 pi included) and the highest order through which the lift is continuous.
// MotionProgram::continuity() fills it; MotionProgram::require_continuity(order) enforces it.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace camfollower {

struct BoundaryContinuity {
    std::size_t left_segment = 0;   // the segment ending at the boundary
    std::size_t right_segment = 0;  // the segment starting there (0 at the wrap)
    double theta = 0.0;             // rad; the wrap is reported at 0
    // h, h', h'', h''' (m/rad^k) as the left segment ends and the right one starts, their jump
    // (right - left) and the tolerance below which a jump counts as none.
    std::array<double, 4> left{}, right{}, jump{}, tolerance{};
    // Highest k such that h .. h^(k) are all continuous: -1 when h itself jumps, 3 for C3 (or better).
    int continuous_through = 3;
};

struct ContinuityReport {
    std::vector<BoundaryContinuity> boundaries;  // boundaries[i]: end of segment i (the last: the wrap)

    // The program's order of continuity: the lowest over its boundaries (3 means C3 at least).
    int continuous_through() const {
        int order = 3;
        for (const BoundaryContinuity& b : boundaries) order = std::min(order, b.continuous_through);
        return order;
    }
};

namespace detail {
inline const char* derivative_name(int order) {
    static constexpr const char* names[] = {"h (lift, m)", "h' (velocity, m/rad)", "h'' (acceleration, m/rad^2)",
                                            "h''' (jerk, m/rad^3)"};
    return names[order];
}
}  // namespace detail

}  // namespace camfollower
