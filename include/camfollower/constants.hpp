// SPDX-License-Identifier: BSD-3-Clause
// Mathematical constants, stated once for the whole library.
#pragma once

namespace camfollower {

inline constexpr double pi = 3.14159265358979323846;

}  // namespace camfollower
