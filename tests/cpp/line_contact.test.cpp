// SPDX-License-Identifier: BSD-3-Clause
// Contact stress against closed forms written out here (Johnson ch. 4 for the line contact, the
// Hertz sphere for the crowned roller's circular limit), Palmgren's formula in its own mm/N units,
// the stress along the paper cam, and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "angles.hpp"
#include "camfollower/contact/line_contact.hpp"
#include "camfollower/follower/translating_flat.hpp"
#include "camfollower/follower/translating_roller.hpp"
#include "camfollower/motion/program.hpp"

using namespace camfollower;
using Catch::Matchers::Contains;

namespace {
const double inf = std::numeric_limits<double>::infinity();
// Steel on steel: E* = E / (2 (1 - nu^2)).
const double E_star_steel = 210e9 / (2.0 * (1.0 - 0.3 * 0.3));
}  // namespace

TEST_CASE("contact modulus adds the two compliances") {
    CHECK(effective_modulus(Elastic::steel(), Elastic::steel()) == Approx(E_star_steel).epsilon(1e-14));
    const Elastic aluminium{70e9, 0.33};
    const double expected = 1.0 / ((1 - 0.09) / 210e9 + (1 - 0.33 * 0.33) / 70e9);
    CHECK(effective_modulus(Elastic::steel(), aluminium) == Approx(expected).epsilon(1e-14));
    CHECK(effective_modulus(aluminium, Elastic::steel()) == Approx(expected).epsilon(1e-14));
}

TEST_CASE("straight roller on a flat: Johnson's line-contact half-width and peak pressure") {
    // Steel roller R = 12.5 mm, L = 10 mm, F = 1000 N on a flat steel surface.
    const LineContact c{0.010, Elastic::steel(), Elastic::steel()};
    const double F = 1000.0, R = 0.0125, L = 0.010;
    const ContactStress s = c.stress(F, R);
    const double b = std::sqrt(4.0 * F * R / (PI * L * E_star_steel));
    CHECK(s.half_width == Approx(b).epsilon(1e-12));
    CHECK(s.max_pressure == Approx(2.0 * F / (PI * b * L)).epsilon(1e-12));
    CHECK(s.max_pressure == Approx(std::sqrt(F * E_star_steel / (PI * L * R))).epsilon(1e-12));
    // Numbers worked by hand: E* = 115.38 GPa, b = 117.4 um, p_max = 542 MPa.
    CHECK(s.half_width == Approx(117.44e-6).epsilon(1e-3));
    CHECK(s.max_pressure == Approx(542.0e6).epsilon(1e-3));
    CHECK(s.effective_radius == R);
    CHECK(s.semi_axis == 0.5 * L);
    CHECK(std::isnan(s.approach));
    // Square-root scaling with the force.
    CHECK(c.stress(4.0 * F, R).max_pressure == Approx(2.0 * s.max_pressure).epsilon(1e-12));
    CHECK(c.stress(0.0, R).max_pressure == 0.0);
}

TEST_CASE("two cylinders: convex adds curvature, concave removes it") {
    const LineContact c{0.010, Elastic::steel(), Elastic::steel()};
    const double F = 2000.0;
    const ContactStress convex = c.stress(F, 0.0125, 0.030);
    const double Rc = 1.0 / (1.0 / 0.0125 + 1.0 / 0.030);
    CHECK(convex.effective_radius == Approx(Rc).epsilon(1e-14));
    CHECK(convex.max_pressure == Approx(std::sqrt(F * E_star_steel / (PI * 0.010 * Rc))).epsilon(1e-12));
    const ContactStress concave = c.stress(F, 0.0125, -0.030);
    const double Rv = 1.0 / (1.0 / 0.0125 - 1.0 / 0.030);
    CHECK(concave.effective_radius == Approx(Rv).epsilon(1e-14));
    CHECK(concave.max_pressure < c.stress(F, 0.0125).max_pressure);  // conforming: lower stress
    CHECK(convex.max_pressure > c.stress(F, 0.0125).max_pressure);
    // Symmetric in the two bodies.
    CHECK(c.stress(F, 0.030, 0.0125).half_width == Approx(convex.half_width).epsilon(1e-14));
}

TEST_CASE("crowned roller: the circular case is the Hertz sphere within the fits' accuracy") {
    // Rx = Ry = r: a sphere of radius r on a flat.
    const double r = 0.0125, F = 1000.0;
    const LineContact c{0.010, Elastic::steel(), Elastic::steel(), r};
    const ContactStress s = c.stress(F, r);
    const double a = std::cbrt(3.0 * F * r / (4.0 * E_star_steel));
    const double p0 = 3.0 * F / (2.0 * PI * a * a);
    const double delta = a * a / r;
    CHECK(s.semi_axis == Approx(a).epsilon(0.03));
    CHECK(s.half_width == Approx(a).epsilon(0.03));
    CHECK(s.max_pressure == Approx(p0).epsilon(0.03));
    // The fits are not exact at alpha = 1 (k = 1.0339 for 1, E(e) = 1.5971 and F(e) = 1.5277 for
    // pi/2): the approach compounds them to 5.4 % low, the largest error of the four.
    CHECK(s.approach == Approx(delta).epsilon(0.06));
    // Exactly the sphere values times those factors: a ~ (k^2 E)^(1/3), b ~ (E/k)^(1/3),
    // delta ~ F (E k^2)^(-1/3) (each relative to the exact pi/2, 1).
    const double k = 1.0339, Ee = 1.0003 + 0.5968, Fe = 1.5277, h = PI / 2.0;
    CHECK(s.semi_axis / a == Approx(std::cbrt(k * k * Ee / h)).epsilon(1e-9));
    CHECK(s.half_width / a == Approx(std::cbrt(Ee / (k * h))).epsilon(1e-9));
    CHECK(s.approach / delta == Approx(Fe / h * std::cbrt(h / (Ee * k * k))).epsilon(1e-9));
    CHECK(s.effective_radius == r);
}

TEST_CASE("crowned roller: the ellipse is long across the width and swaps for a tight crown") {
    const LineContact wide{0.010, Elastic::steel(), Elastic::steel(), 0.5};
    const ContactStress s = wide.stress(1000.0, 0.0125);
    const double alpha = 0.5 / 0.0125;
    CHECK(s.semi_axis / s.half_width == Approx(1.0339 * std::pow(alpha, 0.636)).epsilon(1e-12));
    CHECK(s.max_pressure == Approx(3.0 * 1000.0 / (2.0 * PI * s.semi_axis * s.half_width)).epsilon(1e-12));
    // A crown tighter than the rolling radius: the same ellipse turned by 90 degrees.
    const LineContact tight{0.010, Elastic::steel(), Elastic::steel(), 0.0125};
    const ContactStress t = tight.stress(1000.0, 0.5);
    CHECK(t.half_width == Approx(s.semi_axis).epsilon(1e-12));
    CHECK(t.semi_axis == Approx(s.half_width).epsilon(1e-12));
    CHECK(t.approach == Approx(s.approach).epsilon(1e-12));
}

TEST_CASE("crowned roller: the result reports the radius ratio the fits were evaluated at") {
    // alpha = Ry/Rx (swapped to >= 1), to compare with the fits' range 1 to 100.
    const LineContact crown{0.010, Elastic::steel(), Elastic::steel(), 1.0};
    const double rx = 1.0 / (1.0 / 0.0125 + 1.0 / 0.040);  // 12.5 mm roller on a 40 mm base circle
    const ContactStress s = crown.stress(1000.0, 0.0125, 0.040);
    CHECK(s.radius_ratio == Approx(1.0 / rx).epsilon(1e-12));  // 105: beyond the range
    CHECK(s.radius_ratio > hamrock_brewe_max_ratio);
    const LineContact tight{0.010, Elastic::steel(), Elastic::steel(), 0.0125};
    CHECK(tight.stress(1000.0, 0.5).radius_ratio == Approx(40.0).epsilon(1e-12));  // Rx/Ry: within
    CHECK(std::isnan(LineContact{0.010, Elastic::steel(), Elastic::steel()}.stress(1000.0, 0.0125).radius_ratio));
}

TEST_CASE("Palmgren's roller law in SI reproduces the formula in mm and N") {
    const double L_mm = 10.0, Q = 1000.0;
    const double delta_mm = 3.84e-5 * std::pow(Q, 0.9) / std::pow(L_mm, 0.8);
    const HertzContact law = palmgren_law(L_mm / 1000.0);
    CHECK(law.exponent == 10.0 / 9.0);
    CHECK(law.damping_factor == 0.0);
    CHECK(law.stiffness == palmgren_stiffness(0.010));
    const double delta_m = std::pow(Q / law.stiffness, 9.0 / 10.0);
    CHECK(delta_m * 1000.0 == Approx(delta_mm).epsilon(1e-12));
    CHECK(law(delta_m, 0.0).force == Approx(Q).epsilon(1e-12));
    // Wider roller: stiffer as L^(8/9).
    CHECK(palmgren_stiffness(0.020) / palmgren_stiffness(0.010) == Approx(std::pow(2.0, 8.0 / 9.0)).epsilon(1e-12));
}

TEST_CASE("stress along the paper cam: finite and largest where the surface is tightest") {
    const MotionProgram program = MotionProgram::paper_default();
    const TranslatingRoller roller(0.04, 0.0125, 0.01);
    const LineContact c{0.010, Elastic::steel(), Elastic::steel()};
    std::vector<double> theta;
    for (int i = 0; i < 3600; ++i) theta.push_back(2.0 * PI * i / 3600.0);
    const std::vector<ContactStress> s = profile_stress(c, program, roller, theta, {1000.0});
    REQUIRE(s.size() == theta.size());
    std::size_t i_max = 0, i_min = 0;
    double r_min = inf;
    for (std::size_t i = 0; i < s.size(); ++i) {
        REQUIRE(std::isfinite(s[i].max_pressure));
        REQUIRE(s[i].max_pressure > 0.0);
        if (s[i].max_pressure > s[i_max].max_pressure) i_max = i;
        const FollowerProfilePoint p = roller.profile(theta[i], program.evaluate(theta[i]));
        CHECK(s[i].effective_radius == Approx(p.effective_radius).epsilon(1e-9));
        if (p.surface_radius > 0.0 && p.surface_radius < r_min) r_min = p.surface_radius, i_min = i;
    }
    CHECK(i_max == i_min);
    // At the tightest point the stress is the two-cylinder formula with the cam's radius there.
    const double R = 1.0 / (1.0 / 0.0125 + 1.0 / r_min);
    CHECK(s[i_max].max_pressure == Approx(std::sqrt(1000.0 * E_star_steel / (PI * 0.010 * R))).epsilon(1e-9));
    // Per-angle force.
    const std::vector<double> two{0.0, PI};
    const std::vector<ContactStress> f = profile_stress(c, program, roller, two, {500.0, 2000.0});
    CHECK(f[0].max_pressure == Approx(profile_stress(c, program, roller, 0.0, 500.0).max_pressure));
    CHECK(f[1].max_pressure == Approx(profile_stress(c, program, roller, PI, 2000.0).max_pressure));
}

TEST_CASE("flat-faced follower: the face is a plane (infinite radius)") {
    const MotionProgram program = MotionProgram::paper_default();
    const TranslatingFlat face(0.04);
    const LineContact c{0.010, Elastic::steel(), Elastic::steel()};
    for (double theta : {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}) {
        const ContactStress s = profile_stress(c, program, face, theta, 800.0);
        const double rho = face.profile(theta, program.evaluate(theta)).surface_radius;
        CHECK(s.effective_radius == Approx(rho).epsilon(1e-14));
        CHECK(std::isfinite(s.max_pressure));
    }
}

TEST_CASE("contact stress: bad input names the parameter and its range") {
    const LineContact good{0.010, Elastic::steel(), Elastic::steel()};
    CHECK_THROWS_WITH((LineContact{0.0, Elastic::steel(), Elastic::steel()}.stress(1.0, 0.01)),
                      Contains("roller width (length)") && Contains("> 0"));
    CHECK_THROWS_WITH((LineContact{0.01, Elastic{-1.0, 0.3}, Elastic::steel()}.stress(1.0, 0.01)),
                      Contains("youngs_modulus") && Contains("> 0"));
    CHECK_THROWS_WITH((LineContact{0.01, Elastic::steel(), Elastic{210e9, 0.5}}.stress(1.0, 0.01)),
                      Contains("poisson_ratio must be in [0, 0.5)"));
    CHECK_THROWS_WITH((LineContact{0.01, Elastic::steel(), Elastic::steel(), 0.0}.stress(1.0, 0.01)),
                      Contains("crown_radius must be > 0"));
    CHECK_THROWS_WITH(good.stress(-1.0, 0.01), Contains("contact force") && Contains(">= 0"));
    CHECK_THROWS_WITH(good.stress(1.0, 0.0125, -0.010),
                      Contains("effective radius must be > 0") && Contains("more concave"));
    CHECK_THROWS_WITH(good.stress(1.0, inf, inf), Contains("effective radius must be > 0"));
    CHECK_THROWS_WITH(good.stress(1.0, std::nan("")), Contains("not NaN"));
    CHECK_THROWS_WITH(palmgren_stiffness(-0.01), Contains("roller width (length)"));
    const MotionProgram program = MotionProgram::paper_default();
    CHECK_THROWS_WITH(profile_stress(good, program, TranslatingRoller(0.04, 0.0125, 0.01),
                                     std::vector<double>{0.0, 1.0}, std::vector<double>{1.0, 2.0, 3.0}),
                      Contains("one per angle"));
    CHECK_THROWS_WITH(profile_stress(good, program, TranslatingRoller(0.04, 0.0125, 0.01), 1.0, -5.0),
                      Contains("theta =") && Contains("contact force"));
}
