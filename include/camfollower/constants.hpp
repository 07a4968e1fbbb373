// SPDX-License-Identifier: BSD-3-Clause
// Mathematical constants and the angle conversions, stated once for the whole library.
#pragma once

namespace camfollower {

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double two_pi = 2.0 * pi;
inline constexpr double degrees_to_radians(double deg) { return deg * pi / 180.0; }
inline constexpr double radians_to_degrees(double rad) { return rad * 180.0 / pi; }

}  // namespace camfollower
