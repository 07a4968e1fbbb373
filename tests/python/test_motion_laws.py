# SPDX-License-Identifier: BSD-3-Clause
"""Motion laws through the bindings, against peak coefficients derived here with sympy from each
law's defining conditions (boundary conditions / acceleration shape), independently of the C++ code."""

import math

import camfollower as cf
import numpy as np
import pytest
import sympy as sp

x = sp.symbols("x", real=True)


def polynomial_law(degree, zero_derivatives):
    """Lowest-degree polynomial with S(0)=0, S(1)=1 and the first `zero_derivatives` derivatives zero at both ends."""
    coeffs = sp.symbols(f"a0:{degree + 1}")
    S = sum(c * x**k for k, c in enumerate(coeffs))
    eqs = [S.subs(x, 0), S.subs(x, 1) - 1]
    for k in range(1, zero_derivatives + 1):
        eqs += [sp.diff(S, x, k).subs(x, 0), sp.diff(S, x, k).subs(x, 1)]
    return sp.expand(S.subs(sp.solve(eqs, coeffs)))


def peak_abs(expr):
    """max |expr| on [0, 1] for a smooth expression: critical points and ends."""
    candidates = [sp.Integer(0), sp.Integer(1)]
    for r in sp.solve(sp.diff(expr, x), x):
        if r.is_real and 0 <= r <= 1:
            candidates.append(r)
    return max(abs(sp.N(expr.subs(x, c), 30)) for c in candidates)


def smooth_peaks(S):
    V, A, J = (sp.diff(S, x, k) for k in (1, 2, 3))
    return peak_abs(V), peak_abs(A), peak_abs(J)


def scc_peaks(b, c, d):
    """SCC family from its acceleration shape: integrate piecewise, fix Ca by S(1/2) = 1/2."""
    b, c, d = sp.nsimplify(b), sp.nsimplify(c), sp.nsimplify(d)
    Ca = sp.symbols("Ca", positive=True)
    x1, x2 = b / 2, (1 - d) / 2
    pieces = []
    if b:
        pieces.append((0, x1, Ca * sp.sin(sp.pi * x / b)))
    if x2 > x1:
        pieces.append((x1, x2, Ca))
    if d:
        pieces.append((x2, sp.Rational(1, 2), Ca * sp.cos(sp.pi * (x - x2) / d)))
    v0 = s0 = sp.Integer(0)
    for lo, hi, A in pieces:
        V = v0 + sp.integrate(A, (x, lo, x))
        S = s0 + sp.integrate(V, (x, lo, x))
        v0, s0 = V.subs(x, hi), S.subs(x, hi)
    ca = sp.solve(sp.Eq(s0, sp.Rational(1, 2)), Ca)[0]
    vmax = v0.subs(Ca, ca)  # V peaks where A changes sign: x = 1/2
    if not d:  # A jumps from +Ca to -Ca at x = 1/2
        return sp.N(vmax, 30), sp.N(ca, 30), sp.oo
    # |J| of each piece (a cosine, zero or a sine) peaks at one of its ends.
    jmax = max(abs(sp.diff(A, x).subs(Ca, ca).subs(x, end)) for lo, hi, A in pieces for end in (lo, hi))
    return sp.N(vmax, 30), sp.N(ca, 30), sp.N(jmax, 30)


CASES = [
    ("polynomial_345", lambda: smooth_peaks(polynomial_law(5, 2))),
    ("polynomial_4567", lambda: smooth_peaks(polynomial_law(7, 3))),
    ("cycloidal", lambda: smooth_peaks(x - sp.sin(2 * sp.pi * x) / (2 * sp.pi))),
    ("simple_harmonic", lambda: smooth_peaks((1 - sp.cos(sp.pi * x)) / 2)),
    ("modified_trapezoid", lambda: scc_peaks(0.25, 0.5, 0.25)),
    ("modified_sine", lambda: scc_peaks(0.25, 0, 0.75)),
]


@pytest.mark.parametrize("name,derive", CASES, ids=[c[0] for c in CASES])
def test_peak_coefficients_match_symbolic_derivation(name, derive):
    cv, ca, cj = (float(v) for v in derive())
    p = getattr(cf.MotionLaw, name)().peaks()
    assert p.velocity == pytest.approx(cv, rel=1e-12)
    assert p.acceleration == pytest.approx(ca, rel=1e-12)
    assert p.jerk == pytest.approx(cj, rel=1e-12)


def test_family_parameters_are_free():
    # An arbitrary member, derived symbolically too.
    cv, ca, cj = (float(v) for v in scc_peaks(0.2, 0.3, 0.5))
    p = cf.MotionLaw.sine_constant_cosine(0.2, 0.3, 0.5).peaks()
    assert (p.velocity, p.acceleration, p.jerk) == pytest.approx((cv, ca, cj), rel=1e-12)


def test_vectorized_evaluation_matches_scalar_and_keeps_shape():
    law = cf.MotionLaw.modified_sine()
    xs = np.linspace(0, 1, 12).reshape(3, 4)
    out = law.evaluate(xs)
    assert set(out) == {"S", "V", "A", "J"}
    assert out["A"].shape == (3, 4)
    scalar = law.evaluate(float(xs[1, 2]))
    assert isinstance(scalar["S"], float)
    assert out["A"][1, 2] == scalar["A"]
    # V is dS/dx: integrate V numerically and recover S.
    fine = np.linspace(0, 1, 20001)
    v = law.evaluate(fine)
    s_int = np.concatenate([[0], np.cumsum(0.5 * (v["V"][1:] + v["V"][:-1]) * np.diff(fine))])
    assert np.max(np.abs(s_int - v["S"])) < 1e-8


def test_bad_law_input_raises_value_error_naming_parameter():
    with pytest.raises(ValueError, match=r"b \+ c \+ d must equal 1"):
        cf.MotionLaw.sine_constant_cosine(0.5, 0.5, 0.5)
    with pytest.raises(ValueError, match=r"x must be in \[0, 1\]"):
        cf.MotionLaw.cycloidal().evaluate(np.array([0.5, 1.2]))
    with pytest.raises(ValueError, match="x must be in"):
        cf.MotionLaw.cycloidal().evaluate(math.nan)
