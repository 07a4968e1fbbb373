// SPDX-License-Identifier: BSD-3-Clause
// Error types and argument checks shared by every header.
//
// Bad input throws std::invalid_argument (pybind11 maps it to Python's ValueError) with a message
// that names the parameter and the allowed range. A solver that cannot converge throws
// ConvergenceError (a std::runtime_error, RuntimeError in Python).
#pragma once

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include "camfollower/constants.hpp"

namespace camfollower {

class ConvergenceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

namespace detail {

// One part of a message as text: strings as they are, anything else as `std::ostream <<` prints it,
// numbers with 10 significant digits. Text parts go through the two plain overloads, so the templates
// below are instantiated once per part type, not once per string length and combination of parts
// (each a resolution of `<<` among every overload in scope: minutes of compile time over the library).
inline std::string part_text(const char* s) { return s; }
inline std::string part_text(std::string_view s) { return std::string(s); }
template <class T, std::enable_if_t<!std::is_convertible_v<const T&, std::string_view>, int> = 0>
std::string part_text(const T& part) {
    std::ostringstream out;
    out.precision(10);
    out << part;
    return out.str();
}
inline std::string join(std::initializer_list<std::string> parts) {
    std::string out;
    for (const std::string& p : parts) out += p;
    return out;
}

template <class... Parts>
std::string concat(const Parts&... parts) {
    return join({part_text(parts)...});
}

// Text parts of an error message as they are shown: control characters (terminal escapes, bells,
// NULs) as '?' (newlines kept), at most 1,000 bytes each, so no message carries raw control bytes
// or megabytes of a user's input, whatever the call site passes.
inline std::string message_text(std::string_view s) {
    constexpr std::size_t max = 1000;
    std::string out;
    for (char c : s.substr(0, max)) out += (c != '\n' && (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)) ? '?' : c;
    if (s.size() > max) out += "... (" + std::to_string(s.size()) + " bytes)";
    return out;
}
// A part of an error message: text sanitized (message_text), anything else as concat() shows it.
inline std::string message_part(const char* s) { return message_text(s); }
inline std::string message_part(std::string_view s) { return message_text(s); }
template <class T, std::enable_if_t<!std::is_convertible_v<const T&, std::string_view>, int> = 0>
std::string message_part(const T& part) {
    return part_text(part);
}

template <class... Parts>
[[noreturn]] void fail(const Parts&... parts) {
    throw std::invalid_argument(join({message_part(parts)...}));
}

inline void require_finite(double value, const char* name) {
    if (!std::isfinite(value)) fail(name, " must be finite, got ", value);
}

inline void require_positive(double value, const char* name, const char* unit = "") {
    if (!(std::isfinite(value) && value > 0.0)) fail(name, " must be finite and > 0 ", unit, ", got ", value);
}

inline void require_non_negative(double value, const char* name, const char* unit = "") {
    if (!(std::isfinite(value) && value >= 0.0)) fail(name, " must be finite and >= 0 ", unit, ", got ", value);
}

inline void require_in_range(double value, double lo, double hi, const char* name) {
    if (!(std::isfinite(value) && value >= lo && value <= hi))
        fail(name, " must be in [", lo, ", ", hi, "], got ", value);
}

// The sizes of machine parts the geometry is meant for: a length (radius, arm, diameter, shaft) from
// 1 um to 1 km; far beyond, the curvature formulas lose every digit to cancellation.
inline constexpr double min_part_length = 1e-6, max_part_length = 1e3;  // m
// Forces and preloads of machine elements, N: beyond this a static solution overflows its digits.
inline constexpr double max_force = 1e9;

// Camshaft speeds, rad/s: 1e-6 rad/s (a revolution in 73 days) to 1e5 rad/s (about 955,000 rpm),
// far beyond any machine either way; beyond, the period or the cam angle omega t overflows.
inline constexpr double min_camshaft_speed = 1e-6, max_camshaft_speed = 1e5;
inline void require_camshaft_speed(double omega, const char* name) {
    if (!(std::isfinite(omega) && omega >= min_camshaft_speed && omega <= max_camshaft_speed))
        fail(name, " must be in [", min_camshaft_speed, ", ", max_camshaft_speed, "] rad/s, got ", omega, " rad/s");
}
inline void require_camshaft_speed_rpm(double rpm, const char* name) {
    const double min_rpm = min_camshaft_speed * 30.0 / pi, max_rpm = max_camshaft_speed * 30.0 / pi;
    if (!(std::isfinite(rpm) && rpm >= min_rpm && rpm <= max_rpm))
        fail(name, " must be in [", min_rpm, ", ", max_rpm, "] rpm, got ", rpm);
}

// Points of a sampled curve or outline (profiles, exports, plots): 10 million is 0.13 arc seconds
// apart over a revolution, far finer than any machine; beyond, a typo becomes a memory exhaustion.
inline constexpr long long max_points = 10'000'000;
inline void require_point_count(long long points, long long minimum, const char* name) {
    if (points < minimum || points > max_points)
        fail(name, " must be an integer in [", minimum, ", ", max_points, "], got ", points);
}
inline void require_point_count(std::size_t points, long long minimum, const char* name) {
    if (points > static_cast<std::size_t>(max_points))
        fail(name, " must be an integer in [", minimum, ", ", max_points, "], got ", points);
    require_point_count(static_cast<long long>(points), minimum, name);
}

inline void require_length(double value, const char* name) {
    if (!(std::isfinite(value) && value >= min_part_length && value <= max_part_length))
        fail(name, " must be finite and > 0 (m), in [", min_part_length, ", ", max_part_length, "] m, got ", value);
}
inline void require_offset(double value, const char* name) {
    if (!(std::isfinite(value) && std::abs(value) <= max_part_length))
        fail(name, " must be in [", -max_part_length, ", ", max_part_length, "] m, got ", value);
}
inline void require_force(double value, const char* name) {
    if (!(std::isfinite(value) && std::abs(value) <= max_force))
        fail(name, " must be in [", -max_force, ", ", max_force, "] N, got ", value);
}

// User text as messages echo it: control characters as '?', at most `max` bytes ("..." beyond), so
// an error never carries terminal escapes or megabytes of input.
inline std::string printable(std::string_view s, std::size_t max = 60) {
    std::string out;
    for (char c : s.substr(0, max)) out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
    return s.size() > max ? out + "..." : out;
}

// Names of parts (DOFs, elements, contacts, shafts): what outputs, channels and messages are keyed by.
inline constexpr std::size_t max_name_length = 200;
inline void require_name(const std::string& name, const char* what) {
    bool control = false;
    for (char c : name) control = control || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    if (name.empty() || name.size() > max_name_length || control)
        fail(what, " name must be 1 to ", max_name_length, " printable characters (no control characters), got '",
             printable(name), "' (", name.size(), " bytes)");
}

// "a, b, c, ... (N in all)": at most `max` entries of a list of names, each printable.
template <class Names>
std::string name_list(const Names& names, std::size_t max = 20) {
    std::string out;
    std::size_t n = 0;
    for (const auto& name : names) {
        if (n < max) out += (n ? ", " : "") + printable(name);
        ++n;
    }
    if (n > max) out += detail::concat(", ... (", n, " in all)");
    return n ? out : std::string("none");
}

}  // namespace detail
}  // namespace camfollower
