// SPDX-License-Identifier: BSD-3-Clause
// Third-order Taylor arithmetic: a value with its first three derivatives along one variable, carried
// exactly through +, -, *, /, sqrt, sin, cos, atan2. A closed-form position written once for double
// gives its velocity, acceleration and jerk to rounding when written for Taylor3 (the linkage output's
// SVAJ against the cam angle, composed with the lift's own derivatives).
#pragma once

#include <cmath>

namespace camfollower {

struct Taylor3 {
    double v = 0.0, d1 = 0.0, d2 = 0.0, d3 = 0.0;  // f, f', f'', f'''

    Taylor3() = default;
    Taylor3(double value) : v(value) {}  // NOLINT: a constant converts implicitly, as a double would
    Taylor3(double value, double a, double b, double c) : v(value), d1(a), d2(b), d3(c) {}

    // f(g) for a scalar function with derivatives f0..f3 at g.v (Faa di Bruno to third order).
    Taylor3 chain(double f0, double f1, double f2, double f3) const {
        return {f0, f1 * d1, f1 * d2 + f2 * d1 * d1, f1 * d3 + 3.0 * f2 * d1 * d2 + f3 * d1 * d1 * d1};
    }
};

inline Taylor3 operator+(const Taylor3& a, const Taylor3& b) {
    return {a.v + b.v, a.d1 + b.d1, a.d2 + b.d2, a.d3 + b.d3};
}
inline Taylor3 operator-(const Taylor3& a, const Taylor3& b) {
    return {a.v - b.v, a.d1 - b.d1, a.d2 - b.d2, a.d3 - b.d3};
}
inline Taylor3 operator-(const Taylor3& a) { return {-a.v, -a.d1, -a.d2, -a.d3}; }
inline Taylor3 operator*(const Taylor3& a, const Taylor3& b) {
    return {a.v * b.v, a.d1 * b.v + a.v * b.d1, a.d2 * b.v + 2.0 * a.d1 * b.d1 + a.v * b.d2,
            a.d3 * b.v + 3.0 * a.d2 * b.d1 + 3.0 * a.d1 * b.d2 + a.v * b.d3};
}
inline Taylor3 reciprocal(const Taylor3& a) {
    const double r = 1.0 / a.v;
    return a.chain(r, -r * r, 2.0 * r * r * r, -6.0 * r * r * r * r);
}
inline Taylor3 operator/(const Taylor3& a, const Taylor3& b) { return a * reciprocal(b); }
inline Taylor3 sqrt(const Taylor3& a) {
    const double s = std::sqrt(a.v);
    return a.chain(s, 0.5 / s, -0.25 / (s * a.v), 0.375 / (s * a.v * a.v));
}
inline Taylor3 sin(const Taylor3& a) {
    const double s = std::sin(a.v), c = std::cos(a.v);
    return a.chain(s, c, -s, -c);
}
inline Taylor3 cos(const Taylor3& a) {
    const double s = std::sin(a.v), c = std::cos(a.v);
    return a.chain(c, -s, -c, s);
}
// atan2(y, x) = the angle of (x, y): d = (x y' - y x') / (x^2 + y^2), carried through the quotient.
inline Taylor3 atan2(const Taylor3& y, const Taylor3& x) {
    const Taylor3 rate = (x * Taylor3(y.d1, y.d2, y.d3, 0.0) - y * Taylor3(x.d1, x.d2, x.d3, 0.0)) / (x * x + y * y);
    return {std::atan2(y.v, x.v), rate.v, rate.d1, rate.d2};
}

}  // namespace camfollower
