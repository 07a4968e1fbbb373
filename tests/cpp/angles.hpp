// SPDX-License-Identifier: BSD-3-Clause
// pi and one degree for the tests, written out here rather than taken from the library; one
// definition for all (the tests of a group compile as one unit: tests/cpp/CMakeLists.txt).
#pragma once

inline constexpr double PI = 3.14159265358979323846;
inline constexpr double deg = PI / 180.0;
