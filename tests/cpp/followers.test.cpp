// SPDX-License-Identifier: BSD-3-Clause
// The four follower types against independent truth:
// - a numerical envelope of the follower positions in the cam frame (roller circles or face lines,
//   written out here from each follower's definition, with the arm's start angle found by
//   bisection), for the contact point, the normal (from the envelope's tangent) and the radius of
//   curvature (from three envelope points);
// - central finite differences in theta for dnormal, dlever, dlift, and in s for the lever;
// - textbook limits (flat face g = 0, the roller's closed form of paper eqs 2-5 written out here, a
//   very long arm, dwells), bad input and undercut.
// Every type runs through the same checks from one list (for_each_follower): a new type joins with a
// line there. The translating roller's own checks follow (base circle, the paper cam's extremes, a
// perturbed offset, closure and CSV, a dent narrower than the search's sampling step).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "angles.hpp"
#include "camfollower/follower/oscillating_flat.hpp"
#include "camfollower/follower/oscillating_roller.hpp"
#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/follower/translating_flat.hpp"
#include "camfollower/follower/translating_roller.hpp"
#include "camfollower/geometry/export.hpp"
#include "camfollower/motion/program.hpp"

using namespace camfollower;
using Vec = Eigen::Vector2d;

namespace {

// Plane helpers written out again, so the truth below shares no code with the headers under test.
Vec quarter_turn(const Vec& v) { return {-v.y(), v.x()}; }
double cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec turn(double angle, const Vec& v) {
    return {std::cos(angle) * v.x() - std::sin(angle) * v.y(), std::sin(angle) * v.x() + std::cos(angle) * v.y()};
}
Vec direction(double angle) { return {std::cos(angle), std::sin(angle)}; }

// The paper's program (dwell 0-30, modified-trapezoid rise 30-180, dwell 180-210, return 210-360 deg)
// with a linear lift in m or an angular lift in rad.
const MotionProgram linear_program = MotionProgram::paper_default(0.010);
const MotionProgram angular_program = MotionProgram::paper_default(15.0 * deg);

// Root of g on [-pi, pi] where g increases in the direction of sigma (g(phi0 + sigma eps) > 0):
// a scan for the sign change, then bisection.
template <class G>
double bisect_increasing(const G& g, double sigma) {
    const int n = 7200;
    for (int k = 0; k < n; ++k) {
        double a = -pi + 2 * pi * k / n, b = -pi + 2 * pi * (k + 1) / n;
        if (sigma < 0) std::swap(a, b);  // g must go from < 0 at a to > 0 at b
        if (g(a) < 0 && g(b) >= 0) {
            for (int it = 0; it < 200; ++it) {
                const double mid = 0.5 * (a + b);
                (g(mid) < 0 ? a : b) = mid;
            }
            return 0.5 * (a + b);
        }
    }
    FAIL("no root");
    return 0;
}

// ---- each follower's position from its definition, in the ground frame ----------------------------

struct Circle {
    Vec centre;
    double radius;
};
struct Line {
    Vec point, along, outward;  // outward: the face normal, away from the cam
};

struct TranslatingRollerTruth {
    double rb, rr, e;
    const MotionProgram& program;
    Circle at(double theta) const {
        const double rp = rb + rr;
        return {{e, std::sqrt(rp * rp - e * e) + program.evaluate(theta).h}, rr};
    }
};

struct OscillatingRollerTruth {
    double rb, rr;
    Vec pivot;
    double arm, sigma;
    const MotionProgram& program;
    double phi0 =
        bisect_increasing([this](double phi) { return (pivot + arm * direction(phi)).norm() - (rb + rr); }, sigma);
    Circle at(double theta) const { return {pivot + arm * direction(phi0 + sigma * program.evaluate(theta).h), rr}; }
};

struct TranslatingFlatTruth {
    double rb, g;
    const MotionProgram& program;
    Line at(double theta) const {
        // Tangent to the base circle at lift 0, then moved along the axis (y) by the lift.
        const Vec normal(-std::sin(g), std::cos(g));
        return {rb * normal + Vec(0, program.evaluate(theta).h), Vec(std::cos(g), std::sin(g)), normal};
    }
};

struct OscillatingFlatTruth {
    double rb;
    Vec pivot;
    double f, sigma;
    const MotionProgram& program;
    // The face touches the base circle (support distance rb) and lifting pushes it outwards.
    double phi0 = bisect_increasing([this](double phi) { return direction(phi).dot(pivot) + f - rb; }, sigma);
    Line at(double theta) const {
        const Vec m = direction(phi0 + sigma * program.evaluate(theta).h);
        return {pivot + f * m, quarter_turn(m), m};
    }
};

// ---- the cam surface as the envelope of those positions, in the cam frame --------------------------

Vec to_cam(double theta, const Vec& ground) { return turn(-theta, ground); }

// Neighbouring positions theta -+ eta intersect near the envelope point with an O(eta^2) error;
// Richardson extrapolation in eta^2 removes it.
constexpr double envelope_eta = 5e-4;

template <class Truth>
Vec circle_envelope(const Truth& truth, double theta) {
    auto intersect = [&](double eta) {
        const Circle c1 = truth.at(theta - eta), c2 = truth.at(theta + eta);
        const Vec p1 = to_cam(theta - eta, c1.centre), p2 = to_cam(theta + eta, c2.centre);
        const Vec chord = p2 - p1, mid = 0.5 * (p1 + p2);
        const double half = 0.5 * chord.norm(), r = c1.radius;
        const Vec across = quarter_turn(chord) / chord.norm();
        const Vec a = mid + std::sqrt(r * r - half * half) * across, b = mid - std::sqrt(r * r - half * half) * across;
        return Vec(a.norm() < b.norm() ? a : b);  // the cam-side intersection
    };
    return (4.0 * intersect(envelope_eta / 2) - intersect(envelope_eta)) / 3.0;
}

template <class Truth>
Vec line_envelope(const Truth& truth, double theta) {
    auto intersect = [&](double eta) {
        const Line l1 = truth.at(theta - eta), l2 = truth.at(theta + eta);
        const Vec p1 = to_cam(theta - eta, l1.point), d1 = to_cam(theta - eta, l1.along);
        const Vec p2 = to_cam(theta + eta, l2.point), d2 = to_cam(theta + eta, l2.along);
        return Vec(p1 + cross(p2 - p1, d2) / cross(d1, d2) * d1);
    };
    return (4.0 * intersect(envelope_eta / 2) - intersect(envelope_eta)) / 3.0;
}

Vec envelope(const TranslatingRollerTruth& t, double theta) { return circle_envelope(t, theta); }
Vec envelope(const OscillatingRollerTruth& t, double theta) { return circle_envelope(t, theta); }
Vec envelope(const TranslatingFlatTruth& t, double theta) { return line_envelope(t, theta); }
Vec envelope(const OscillatingFlatTruth& t, double theta) { return line_envelope(t, theta); }

// Direction from the cam towards the follower at the contact, cam frame, from the definition only:
// towards the roller centre, or the face's outward normal. Used only to orient the envelope normal.
Vec outward(const TranslatingRollerTruth& t, double theta) {
    return to_cam(theta, t.at(theta).centre) - envelope(t, theta);
}
Vec outward(const OscillatingRollerTruth& t, double theta) {
    return to_cam(theta, t.at(theta).centre) - envelope(t, theta);
}
Vec outward(const TranslatingFlatTruth& t, double theta) { return to_cam(theta, t.at(theta).outward); }
Vec outward(const OscillatingFlatTruth& t, double theta) { return to_cam(theta, t.at(theta).outward); }

struct EnvelopeErrors {
    double point = 0;      // m
    double normal = 0;     // |n - n_envelope|
    double curvature = 0;  // |kappa - kappa_envelope| / max(|kappa|, 1/r_b)
};

// Closed-form profile and contact against the envelope at 720 cam angles (none within 0.2 deg of a
// segment end, where the jerk jumps and the sampled truth loses its smoothness). Observed with gcc
// -O2 over all geometries below: point <= 1.3e-13 m, normal <= 6.7e-12, curvature <= 1.4e-8
// relative; the tests allow ten times that (1e-12 m, 1e-10, 1e-7).
template <class Follower, class Truth>
EnvelopeErrors compare_with_envelope(const Follower& follower, const Truth& truth, const MotionProgram& program,
                                     double rb) {
    EnvelopeErrors worst;
    for (int k = 0; k < 720; ++k) {
        const double theta = (k + 0.41) * 0.5 * deg;
        const FollowerMotion m = program.evaluate(theta);
        const FollowerProfilePoint p = follower.profile(theta, m);
        const ContactGeometry c = follower.contact(theta, m);
        const Vec env = envelope(truth, theta);
        worst.point = std::max(worst.point, (p.surface - env).norm());
        worst.point = std::max(worst.point, (p.contact_ground - turn(theta, env)).norm());

        // Normal: perpendicular to the envelope's tangent (central difference, Richardson).
        auto derivative = [&](double d) {
            return Vec((envelope(truth, theta + d) - envelope(truth, theta - d)) / (2 * d));
        };
        const double delta = 1e-3;
        const Vec tangent = (4.0 * derivative(delta / 2) - derivative(delta)) / 3.0;
        Vec n_env = quarter_turn(tangent).normalized();
        if (n_env.dot(outward(truth, theta)) < 0) n_env = -n_env;
        worst.normal = std::max(worst.normal, (c.normal - turn(theta, n_env)).norm());

        // Curvature of the circle through three envelope points, signed > 0 where the centre of
        // curvature is on the cam side (the second difference points against the outward normal).
        auto curvature = [&](double d) {
            const Vec a = envelope(truth, theta - d), b = envelope(truth, theta), e = envelope(truth, theta + d);
            const double kappa = 2 * std::abs(cross(b - a, e - b)) / ((b - a).norm() * (e - b).norm() * (e - a).norm());
            return (a + e - 2 * b).dot(n_env) < 0 ? kappa : -kappa;
        };
        const double kappa_env = (4.0 * curvature(delta / 2) - curvature(delta)) / 3.0;
        const double kappa = 1.0 / p.surface_radius;
        worst.curvature = std::max(worst.curvature, std::abs(kappa - kappa_env) / std::max(std::abs(kappa), 1.0 / rb));
    }
    return worst;
}

// The profile's reference point: the roller centre, or a point on the face line.
double reference_error(const TranslatingRollerTruth& t, const FollowerProfilePoint& p) {
    return (p.reference - to_cam(p.theta, t.at(p.theta).centre)).norm();
}
double reference_error(const OscillatingRollerTruth& t, const FollowerProfilePoint& p) {
    return (p.reference - to_cam(p.theta, t.at(p.theta).centre)).norm();
}
template <class LineTruth>
double reference_error(const LineTruth& t, const FollowerProfilePoint& p) {
    const Line l = t.at(p.theta);
    return std::abs((turn(p.theta, p.reference) - l.point).dot(l.outward));
}

// Largest relative error of dnormal, dlever, dlift against central differences of contact().
struct DerivativeErrors {
    double dnormal = 0, dlever = 0, dlift = 0;
};
template <class Follower>
DerivativeErrors compare_with_differences(const Follower& follower, const MotionProgram& program, double lever_scale,
                                          double lift_scale) {
    DerivativeErrors worst;
    const double h = 1e-5;
    for (int k = 0; k < 360; ++k) {
        const double theta = (k + 0.37) * deg;
        const ContactGeometry c = follower.contact(theta, program.evaluate(theta));
        const ContactGeometry up = follower.contact(theta + h, program.evaluate(theta + h));
        const ContactGeometry down = follower.contact(theta - h, program.evaluate(theta - h));
        const Vec dn = (up.normal - down.normal) / (2 * h);
        const double dlever = (up.lever - down.lever) / (2 * h), dlift = (up.lift - down.lift) / (2 * h);
        worst.dnormal = std::max(worst.dnormal, (c.dnormal - dn).norm() / std::max(c.dnormal.norm(), 1e-2));
        worst.dlever =
            std::max(worst.dlever, std::abs(c.dlever - dlever) / std::max(std::abs(c.dlever), 1e-2 * lever_scale));
        worst.dlift = std::max(worst.dlift, std::abs(c.dlift - dlift) / std::max(std::abs(c.dlift), 1e-2 * lift_scale));
    }
    return worst;
}

// lever = n . dX/ds with X the follower's contact point carried along by the follower's own motion
// (translation along y, or rotation about the pivot), by central differences in s at fixed theta.
template <class Follower, class Carry>
double lever_error(const Follower& follower, const MotionProgram& program, const Carry& carry) {
    double worst = 0;
    const double ds = 1e-6;
    for (int k = 0; k < 360; ++k) {
        const double theta = (k + 0.29) * deg;
        const FollowerMotion m = program.evaluate(theta);
        const ContactGeometry c = follower.contact(theta, m);
        const Vec X = follower.profile(theta, m).contact_ground;
        const double lever = c.normal.dot((carry(X, ds) - carry(X, -ds)) / (2 * ds));
        worst = std::max(worst, std::abs(c.lever - lever) / std::abs(c.lever));
    }
    return worst;
}

const auto translate = [](const Vec& X, double ds) { return Vec(X + Vec(0, ds)); };
auto swing(const Vec& pivot, double sigma) {
    return [pivot, sigma](const Vec& X, double ds) { return Vec(pivot + turn(sigma * ds, X - pivot)); };
}

// The number after "theta = " in an error message.
double theta_in(const std::string& message) {
    const auto at = message.find("theta = ");
    REQUIRE(at != std::string::npos);
    return std::stod(message.substr(at + 8));
}
template <class F>
std::string message_of(const F& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

// Realistic geometry (m).
const Vec pivot(0.070, 0.040);

// Programs a type is refused on: a 40 mm (0.5 rad) cycloidal rise over 40 deg on a 10 mm base circle
// (rollers undercut), 10 mm over 60 deg (a flat face cusps: r_b + h + h'' < 0), and an arm swinging
// 1 rad in 60 deg (faster than the cam turns).
const MotionProgram steep({{MotionLaw::cycloidal(), 0, 40 * deg, 0, 0.04},
                           {MotionLaw::cycloidal(), 40 * deg, 2 * pi, 0.04, 0.0}});
const MotionProgram steep_swing({{MotionLaw::cycloidal(), 0, 40 * deg, 0, 0.5},
                                 {MotionLaw::cycloidal(), 40 * deg, 2 * pi, 0.5, 0.0}});
const MotionProgram fast({{MotionLaw::cycloidal(), 0, 60 * deg, 0, 0.01},
                          {MotionLaw::dwell(), 60 * deg, 120 * deg, 0.01, 0.01},
                          {MotionLaw::polynomial_345(), 120 * deg, 2 * pi, 0.01, 0.0}});
const MotionProgram whip({{MotionLaw::cycloidal(), 0, 60 * deg, 0, 1.0},
                          {MotionLaw::cycloidal(), 60 * deg, 2 * pi, 1.0, 0.0}});
// A 20 mm cycloidal rise over 100 deg for a roller on a small base circle (25 mm, roller 6 mm): strong
// curvature and concave flanks, where the paper cam has neither.
const MotionProgram aggressive({{MotionLaw::cycloidal(), 0, 100 * deg, 0, 0.02},
                                {MotionLaw::dwell(), 100 * deg, 160 * deg, 0.02, 0.02},
                                {MotionLaw::polynomial_345(), 160 * deg, 2 * pi, 0.02, 0.0}});

// ---- every follower type, one list ------------------------------------------------------------------
// Each type with a few geometries: the follower, its truth written from its definition (above), the
// program it lifts by, how its contact point moves with the lift (carry), its base radius, and a
// geometry of that type with a program it must be refused on. The suite below runs each entry
// through every check; a new follower type joins them with its line here (and its truth above).
template <class Visit>
void for_each_follower(Visit&& visit) {
    for (double e : {0.010, 0.0, -0.006})
        visit("translating roller, offset " + std::to_string(e), TranslatingRoller(0.030, 0.008, e),
              TranslatingRollerTruth{0.030, 0.008, e, linear_program}, linear_program, translate, 0.030,
              TranslatingRoller(0.010, 0.012, 0.0), steep);
    for (double e : {0.008, -0.005})
        visit("translating roller on the aggressive cam, offset " + std::to_string(e),
              TranslatingRoller(0.025, 0.006, e), TranslatingRollerTruth{0.025, 0.006, e, aggressive}, aggressive,
              translate, 0.025, TranslatingRoller(0.010, 0.012, 0.0), steep);
    for (double g : {0.0, 10 * deg, -25 * deg})
        visit("translating flat, face angle " + std::to_string(g / deg), TranslatingFlat(0.035, g, 0.005),
              TranslatingFlatTruth{0.035, g, linear_program}, linear_program, translate, 0.035, TranslatingFlat(0.010),
              fast);
    for (ArmTurn sense : {ArmTurn::counter_clockwise, ArmTurn::clockwise}) {
        const double sigma = sense == ArmTurn::counter_clockwise ? 1.0 : -1.0;
        for (double arm : {0.060, 0.095})
            visit("oscillating roller, sigma " + std::to_string(sigma) + ", arm " + std::to_string(arm),
                  OscillatingRoller(0.035, 0.008, pivot, arm, sense),
                  OscillatingRollerTruth{0.035, 0.008, pivot, arm, sigma, angular_program}, angular_program,
                  swing(pivot, sigma), 0.035, OscillatingRoller(0.010, 0.012, Vec(0.05, 0.03), 0.05, sense),
                  steep_swing);
        for (double f : {0.0, 0.006, -0.004})
            visit("oscillating flat, sigma " + std::to_string(sigma) + ", face offset " + std::to_string(f),
                  OscillatingFlat(0.035, pivot, f, sense),
                  OscillatingFlatTruth{0.035, pivot, f, sigma, angular_program}, angular_program, swing(pivot, sigma),
                  0.035, OscillatingFlat(0.035, pivot, 0.0, sense), whip);
    }
}

// A roller's pressure angle and lever are defined with its centre's velocity (the centre lies on the
// normal line); a face's with the contact point's.
template <class Follower>
Vec driven_point(const Follower& follower, double theta, const FollowerMotion& m) {
    const FollowerProfilePoint p = follower.profile(theta, m);
    return std::isfinite(follower.follower_radius()) ? turn(theta, p.reference) : p.contact_ground;
}
}  // namespace

// ---------------------------------------------------------------------------------------------------
TEST_CASE("every follower type: closed form against the envelope of its positions") {
    for_each_follower([](const std::string& name, const auto& follower, const auto& truth, const MotionProgram& program,
                         const auto&, double rb, const auto&, const MotionProgram&) {
        INFO(name);
        if constexpr (std::is_same_v<std::decay_t<decltype(truth)>, OscillatingRollerTruth> ||
                      std::is_same_v<std::decay_t<decltype(truth)>, OscillatingFlatTruth>)
            CHECK(std::abs(std::remainder(follower.start_angle() - truth.phi0, 2 * pi)) < 1e-13);
        const EnvelopeErrors err = compare_with_envelope(follower, truth, program, rb);
        INFO("point " << err.point << " m, normal " << err.normal << ", curvature " << err.curvature);
        CHECK(err.point < 1e-12);
        CHECK(err.normal < 1e-10);
        CHECK(err.curvature < 1e-7);
        for (double t : {1.3, 2.1, 2.5})
            CHECK(reference_error(truth, follower.profile(t, program.evaluate(t))) < 1e-14);
    });
}

TEST_CASE(
    "every follower type: a name of its own in Follower, its description, a lift in m exactly when it translates") {
    std::set<std::string> seen;
    for_each_follower([&](const std::string& name, const auto& follower, const auto&, const MotionProgram&,
                          const auto& carry, double rb, const auto&, const MotionProgram&) {
        INFO(name);
        using F = std::decay_t<decltype(follower)>;
        // Its carry moves the driven point along y for any position: a translation, else a swing.
        const bool translates = (carry(Vec(0.3, -0.2), 1e-3) - Vec(0.3, -0.2 + 1e-3)).norm() < 1e-15;
        CHECK(is_translating(follower) == translates);
        CHECK(is_translating(Follower(follower)) == translates);
        CHECK(std::string(follower_type_name(Follower(follower))) == F::type_name);
        const std::string line = describe_follower(follower, LengthUnit::mm);
        CHECK(line.rfind(std::string(F::type_name) + ": base_radius = " + std::to_string(int(rb * 1000)), 0) == 0);
        seen.insert(F::type_name);
    });
    // The barrel cams' followers (their geometry is checked in barrel.test.cpp).
    const Follower carriage = BarrelRoller(0.06, 0.016, 0.01),
                   arm = BarrelArmRoller(0.06, 0.016, 0.01, Vec(-0.1, 0), 0.12);
    CHECK(is_translating(carriage));
    CHECK_FALSE(is_translating(arm));
    for (const Follower& f : {carriage, arm}) {
        const std::string type = follower_type_name(f);
        CHECK(describe_follower(f, LengthUnit::mm).rfind(type + ": cylinder_radius = 6", 0) == 0);
        seen.insert(type);
    }
    const std::vector<std::string> all = follower_type_names();
    CHECK(std::set<std::string>(all.begin(), all.end()) == seen);  // distinct, and each one tried above
    CHECK(all.size() == std::variant_size_v<Follower>);
}

TEST_CASE("every follower type: dnormal, dlever, dlift against central differences of contact()") {
    for_each_follower([](const std::string& name, const auto& follower, const auto&, const MotionProgram& program,
                         const auto&, double, const auto&, const MotionProgram&) {
        INFO(name);
        // Scales for the relative errors: the largest lever and the program's lift.
        double lever_scale = 0;
        for (int k = 0; k < 360; ++k)
            lever_scale = std::max(lever_scale, std::abs(follower.contact(k * deg, program.evaluate(k * deg)).lever));
        const DerivativeErrors err = compare_with_differences(follower, program, lever_scale, program.max_lift());
        INFO("dnormal " << err.dnormal << ", dlever " << err.dlever << ", dlift " << err.dlift);
        CHECK(err.dnormal < 1e-6);
        CHECK(err.dlever < 1e-6);
        CHECK(err.dlift < 1e-6);
    });
}

TEST_CASE("every follower type: lever = n . dX/ds of its driven point, by differences in s") {
    for_each_follower([](const std::string& name, const auto& follower, const auto&, const MotionProgram& program,
                         const auto& carry, double, const auto&, const MotionProgram&) {
        INFO(name);
        CHECK(lever_error(follower, program, carry) < 1e-9);
    });
}

TEST_CASE("every follower type: pressure angle = angle from the driven point's velocity to the normal") {
    for_each_follower([](const std::string& name, const auto& follower, const auto&, const MotionProgram& program,
                         const auto& carry, double, const auto&, const MotionProgram&) {
        INFO(name);
        double worst = 0;
        for (int k = 0; k < 360; ++k) {
            const double theta = (k + 0.29) * deg;
            const FollowerMotion m = program.evaluate(theta);
            const ContactGeometry c = follower.contact(theta, m);
            const Vec X = driven_point(follower, theta, m);
            const Vec v = carry(X, 1e-6) - carry(X, -1e-6);
            const double alpha = std::atan2(cross(v, c.normal), v.dot(c.normal));
            worst = std::max({worst, std::abs(alpha - c.pressure_angle()),
                              std::abs(alpha - follower.profile(theta, m).pressure_angle)});
            CHECK(c.cos_alpha * c.cos_alpha + c.sin_alpha * c.sin_alpha == Approx(1.0).epsilon(1e-14));
        }
        CHECK(worst < 1e-9);
    });
}

TEST_CASE("every follower type: sampled extremes agree with brute force; an undercut or cusp is refused") {
    for_each_follower([](const std::string& name, const auto& follower, const auto&, const MotionProgram& program,
                         const auto&, double, const auto& refused, const MotionProgram& refused_on) {
        INFO(name);
        double alpha = 0, reff = 1;
        for (int k = 0; k < 36000; ++k) {
            const double theta = k * 1e-2 * deg;
            const FollowerProfilePoint p = follower.profile(theta, program.evaluate(theta));
            if (std::abs(p.pressure_angle) > std::abs(alpha)) alpha = p.pressure_angle;
            reff = std::min(reff, p.effective_radius);
        }
        // The sampled extremes refine between samples: at least as extreme, and close.
        CHECK(std::abs(max_pressure_angle(program, follower).value) >= std::abs(alpha) - 1e-12);
        CHECK(max_pressure_angle(program, follower).value == Approx(alpha).epsilon(1e-6));
        CHECK(min_effective_radius(program, follower).value <= reff + 1e-15);
        CHECK(min_effective_radius(program, follower).value == Approx(reff).epsilon(1e-6));
        CHECK_NOTHROW(check_undercut(program, follower));
        CHECK_THROWS_WITH(check_undercut(refused_on, refused), Catch::Contains("theta = "));
    });
}

TEST_CASE("translating flat: its reference point lies on the follower axis") {
    const TranslatingFlat follower(0.035, 10 * deg, 0.005);
    for (double t : {0.4, 2.1, 4.0})
        CHECK(turn(t, follower.profile(t, linear_program.evaluate(t)).reference).x() == Approx(0.005).epsilon(1e-13));
}

// ---------------------------------------------------------------------------------------------------
TEST_CASE("textbook: flat face with g = 0 touches at x = h' and rho = r_b + h + h''") {
    const double rb = 0.035, e = 0.004;
    const TranslatingFlat follower(rb, 0.0, e);
    for (int k = 0; k < 3600; ++k) {
        const double theta = k * 0.1 * deg;
        const FollowerMotion m = linear_program.evaluate(theta);
        const FollowerProfilePoint p = follower.profile(theta, m);
        CHECK(p.contact_ground.x() == Approx(m.dh).margin(1e-17));
        CHECK(p.contact_ground.y() == Approx(rb + m.h).epsilon(1e-15));
        CHECK(p.surface_radius == Approx(rb + m.h + m.d2h).epsilon(1e-14));
        CHECK(p.pressure_angle == 0.0);
        CHECK(follower.face_position(m) == Approx(m.dh - e).margin(1e-17));
    }
    // Its tightest convex spot, by brute-force sampling of the textbook formula.
    double sampled = 1, at = 0;
    for (int k = 0; k < 360000; ++k) {
        const double theta = k * 1e-3 * deg;
        const FollowerMotion m = linear_program.evaluate(theta);
        if (rb + m.h + m.d2h < sampled) sampled = rb + m.h + m.d2h, at = theta;
    }
    const AngleExtremum tightest = min_surface_radius(linear_program, follower);
    CHECK(tightest.value == Approx(sampled).epsilon(1e-9));
    CHECK(tightest.theta == Approx(at).margin(2e-3 * deg));
}

TEST_CASE("textbook: the translating roller is the paper's closed form (eqs 2-5)") {
    const double rb = 0.030, rr = 0.008;
    for (double e : {0.010, 0.0, -0.007}) {
        INFO("offset " << e);
        const TranslatingRoller follower(rb, rr, e);
        // eq 2: the roller centre's height on the base circle.
        const double s0 = std::sqrt((rb + rr) * (rb + rr) - e * e);
        CHECK(follower.pitch_base() == Approx(s0).epsilon(1e-15));
        for (int k = 0; k < 3600; ++k) {
            const double theta = k * 0.1 * deg;
            const FollowerMotion m = linear_program.evaluate(theta);
            // eqs 3-4: R = s0 + h, alpha = atan((R' - e) / R) and its theta-derivative; the pitch
            // curve's curvature (> 0 convex).
            const double R = s0 + m.h, p = m.dh - e, norm2 = R * R + p * p;
            const double alpha = std::atan2(p, R);
            const double dalpha = (m.d2h * R - p * m.dh) / norm2;
            const double kappa = (R * R + p * (2 * m.dh - e) - R * m.d2h) / (norm2 * std::sqrt(norm2));
            const ContactGeometry c = follower.contact(theta, m);
            CHECK(std::abs(c.pressure_angle() - alpha) <= 1e-14);
            CHECK((c.normal - Vec(-std::sin(alpha), std::cos(alpha))).norm() <= 1e-14);
            CHECK(std::abs(c.lever - std::cos(alpha)) <= 1e-15);
            CHECK((c.dnormal + dalpha * Vec(std::cos(alpha), std::sin(alpha))).norm() <= 1e-15);
            CHECK(std::abs(c.dlever + std::sin(alpha) * dalpha) <= 1e-15);
            // eq 5, in the cam frame X_cam = Rot(-theta) X_ground: the roller centre (e, R) and the
            // surface point r_r from it against the normal.
            const Vec pitch(R * std::sin(theta) + e * std::cos(theta), R * std::cos(theta) - e * std::sin(theta));
            const Vec surface = pitch - rr * Vec(std::sin(theta - alpha), std::cos(theta - alpha));
            const FollowerProfilePoint q = follower.profile(theta, m);
            CHECK((q.reference - pitch).norm() <= 1e-15);
            CHECK((q.surface - surface).norm() <= 1e-15);
            CHECK(q.surface_radius == Approx(1.0 / kappa - rr).epsilon(1e-13));
        }
        // The checks' extremes against the same closed form sampled every 1e-3 deg: the steepest
        // pressure angle, and the tightest convex spot (largest pitch curvature: the effective radius
        // r_r (1 - r_r kappa) is least there).
        double alpha_max = 0, kappa_max = -std::numeric_limits<double>::infinity();
        for (int k = 0; k < 360000; ++k) {
            const FollowerMotion m = linear_program.evaluate(k * 1e-3 * deg);
            const double R = s0 + m.h, p = m.dh - e, norm2 = R * R + p * p;
            alpha_max = std::max(alpha_max, std::abs(std::atan2(p, R)));
            kappa_max = std::max(kappa_max, (R * R + p * (2 * m.dh - e) - R * m.d2h) / (norm2 * std::sqrt(norm2)));
        }
        CHECK(std::abs(max_pressure_angle(linear_program, follower).value) == Approx(alpha_max).epsilon(1e-9));
        CHECK(min_surface_radius(linear_program, follower).value == Approx(1.0 / kappa_max - rr).epsilon(1e-7));
    }
}

TEST_CASE("textbook: an oscillating roller on a very long arm approaches the translating roller") {
    // Pivot straight across from the roller's base position, at distance L along +x: the roller
    // swings through s = h/L rad on an arc of radius L, which flattens into the axis x = e. Two
    // first-order effects separate the pressure angles: the lifting direction leans from the axis by
    // s = h/L, and the arc drifts sideways by h^2/(2L) while the centre's velocity gains a lateral
    // h' h/L, turning the normal back a little. To first order in 1/L, on the top dwell (h' = 0,
    // R = s0 + h_max):  alpha_osc - alpha_trans = (h_max/L) [1 - h_max R / (2 (R^2 + e^2))]
    // = 0.8975 h_max/L here. So: |alpha_osc - alpha_trans| < h_max/L everywhere (measured max
    // 0.8977 h_max/L, near the end of the rise), tenfold smaller for a tenfold longer arm, and the
    // dwell value matches the prediction to O(1/L^2) (measured 5e-5 h_max/L^2). Beyond L ~ 1e3 m the
    // pivot's rounding (eps L) starts to show, so the arm stops at 100 m.
    const double rb = 0.030, rr = 0.008, e = 0.010, h_max = 0.010;
    const double s0 = std::sqrt((rb + rr) * (rb + rr) - e * e), R = s0 + h_max;
    const double first_order = 1.0 - h_max * R / (2.0 * (R * R + e * e));
    const TranslatingRoller straight(rb, rr, e);
    double previous = 0;
    for (double L : {1.0, 10.0, 100.0}) {
        const MotionProgram program = MotionProgram::paper_default(h_max / L);
        const OscillatingRoller swinging(rb, rr, Vec(e + L, s0), L, ArmTurn::clockwise);
        const auto difference = [&](double theta) {
            return swinging.contact(theta, program.evaluate(theta)).pressure_angle() -
                   straight.contact(theta, linear_program.evaluate(theta)).pressure_angle();
        };
        double worst = 0;
        for (int k = 0; k < 3600; ++k) worst = std::max(worst, std::abs(difference(k * 0.1 * deg)));
        const double dwell = difference(195 * deg) * L / h_max;
        INFO("L = " << L << " m: max |alpha_osc - alpha_trans| = " << worst << " rad = " << worst * L / h_max
                    << " h_max/L; top dwell " << dwell << " h_max/L, predicted " << first_order);
        CHECK(worst < h_max / L);
        CHECK(std::abs(dwell - first_order) < 1e-4 / L + 2e-6);
        if (previous > 0) CHECK(previous / worst == Approx(10.0).epsilon(1e-3));  // first order in 1/L
        previous = worst;
    }
}

TEST_CASE("dwells: pressure angles") {
    for (double theta : {5 * deg, 20 * deg, 185 * deg, 205 * deg}) {
        INFO("theta " << theta / deg);
        const FollowerMotion lin = linear_program.evaluate(theta), ang = angular_program.evaluate(theta);
        CHECK(TranslatingRoller(0.030, 0.008, 0.0).contact(theta, lin).pressure_angle() == 0.0);
        CHECK(TranslatingFlat(0.035, 0.0, 0.005).contact(theta, lin).pressure_angle() == 0.0);
        CHECK(std::abs(OscillatingFlat(0.035, pivot, 0.0).contact(theta, ang).pressure_angle()) < 1e-15);
        // Not zero in general: an inclined face keeps alpha = g; a face off the pivot by f touches a
        // dwell (a circle about the cam centre) at the foot of the perpendicular from the cam centre,
        // p m0, whose velocity about the pivot leans from m0.
        CHECK(TranslatingFlat(0.035, 12 * deg, 0.005).contact(theta, lin).pressure_angle() ==
              Approx(12 * deg).epsilon(1e-15));
        for (double sigma : {1.0, -1.0}) {
            const double f = 0.006;
            const OscillatingFlatTruth truth{0.035, pivot, f, sigma, angular_program};
            const Vec m0 = direction(truth.phi0 + sigma * ang.h), X = (m0.dot(pivot) + f) * m0;
            if (ang.h == 0.0) CHECK(X.norm() == Approx(0.035).epsilon(1e-12));  // on the base circle
            const Vec v = sigma * quarter_turn(X - pivot);
            const OscillatingFlat follower(0.035, pivot, f,
                                           sigma > 0 ? ArmTurn::counter_clockwise : ArmTurn::clockwise);
            CHECK(follower.contact(theta, ang).pressure_angle() ==
                  Approx(std::atan2(cross(v, m0), v.dot(m0))).epsilon(1e-12));
            CHECK((follower.profile(theta, ang).contact_ground - X).norm() < 1e-15);
        }
    }
    // With the face through the pivot the pressure angle is zero all the way round.
    const OscillatingFlat through_pivot(0.035, pivot, 0.0, ArmTurn::clockwise);
    CHECK(std::abs(max_pressure_angle(angular_program, through_pivot).value) < 1e-15);
}

// ---- the translating roller beyond the shared checks -----------------------------------------------
TEST_CASE("translating roller: on the dwell the surface is the base circle and alpha = atan(-e/s0)") {
    const TranslatingRoller roller(0.030, 0.008, 0.010);
    const double s0 = std::sqrt(0.038 * 0.038 - 0.01 * 0.01);
    for (double t : {5 * deg, 20 * deg}) {
        const FollowerMotion m = linear_program.evaluate(t);
        const FollowerProfilePoint p = roller.profile(t, m);
        CHECK(roller.kinematics(m).R == Approx(s0).epsilon(1e-15));
        CHECK(p.surface.norm() == Approx(0.030).epsilon(1e-14));
        CHECK(p.reference.norm() == Approx(0.038).epsilon(1e-14));
        CHECK(p.pressure_angle == Approx(std::atan(-0.01 / s0)).epsilon(1e-14));
        CHECK(p.surface_radius == Approx(0.030).epsilon(1e-12));
    }
}

TEST_CASE("translating roller: the paper cam's steepest pressure angle lies on the right segment") {
    // The paper's return (210-360 deg) mirrors its rise (30-180 deg). A positive offset raises the
    // return's magnitude: with e = +10 mm the steepest angle is on the return, negative; mirrored,
    // e = -10 mm puts it on the rise, positive, with the same magnitude.
    const double rb = 0.030, rr = 0.008, e = 0.010, s0 = std::sqrt(0.038 * 0.038 - e * e);
    const TranslatingRoller plus(rb, rr, e), minus(rb, rr, -e);
    const AngleExtremum ret = max_pressure_angle(linear_program, plus);
    const AngleExtremum rise = max_pressure_angle(linear_program, minus);
    CHECK(ret.theta >= 210 * deg);
    CHECK(ret.value < 0.0);
    CHECK(rise.theta >= 30 * deg);
    CHECK(rise.theta <= 180 * deg);
    CHECK(rise.value > 0.0);
    CHECK(rise.value == Approx(-ret.value).epsilon(1e-12));
    // Sampled every 1e-3 deg over each segment.
    double sampled_rise = 0, sampled_ret = 0, plus_on_rise = 0;
    bool negative_on_rise = true;
    for (int k = 0; k <= 360000; ++k) {
        const double t = k * 1e-3 * deg;
        const FollowerMotion m = linear_program.evaluate(t);
        const double a_plus = plus.profile(t, m).pressure_angle, a_minus = minus.profile(t, m).pressure_angle;
        if (t >= 30 * deg && t <= 180 * deg) {
            sampled_rise = std::max(sampled_rise, std::abs(a_minus));
            plus_on_rise = std::max(plus_on_rise, std::abs(a_plus));
            negative_on_rise = negative_on_rise && a_plus < 0.0;
        }
        if (t >= 210 * deg) sampled_ret = std::max(sampled_ret, std::abs(a_plus));
    }
    CHECK(rise.value == Approx(sampled_rise).epsilon(1e-9));
    CHECK(-ret.value == Approx(sampled_ret).epsilon(1e-9));
    // e = 10 mm exceeds the peak R' = 2 h_max / beta = 7.6 mm/rad: with e = +10 mm alpha < 0 all along
    // the rise, its magnitude largest where the rise leaves the base circle, atan(e / s0).
    CHECK(negative_on_rise);
    CHECK(plus_on_rise == Approx(std::atan(e / s0)).epsilon(1e-12));
    // The base circle is the tightest convex spot of this cam.
    CHECK(min_surface_radius(linear_program, plus).value == Approx(0.030).epsilon(1e-12));
}

TEST_CASE("translating roller: a perturbed offset e* is a roller built with that offset, base circle unchanged") {
    // The paper's perturbed offset (eqs 8-18) enters through kinematics_from(m, s0*, e*),
    // s0* = sqrt((r_b + r_r)^2 - e*^2).
    const double rb = 0.030, rr = 0.008, rp = rb + rr, de = 10e-6;
    for (double e_star : {0.010 + de, 0.010 - de}) {
        INFO("e* = " << e_star);
        const double s0_star = std::sqrt(rp * rp - e_star * e_star);
        const TranslatingRoller shifted(rb, rr, e_star);
        CHECK(shifted.pitch_base() == Approx(s0_star).epsilon(1e-15));
        for (double t : {10 * deg, 70 * deg, 250 * deg}) {
            const FollowerMotion m = linear_program.evaluate(t);
            const ContactKinematics k = TranslatingRoller::kinematics_from(m, s0_star, e_star);
            CHECK(k.pressure_angle() == Approx(shifted.contact(t, m).pressure_angle()).epsilon(1e-15));
            // The surface point: r_r from the roller centre (e*, R) against the normal, in the cam frame.
            const Vec surface = turn(-t, Vec(e_star, k.R) - rr * Vec(-k.sin_alpha, k.cos_alpha));
            CHECK((shifted.profile(t, m).surface - surface).norm() < 1e-15);
            CHECK(TranslatingRoller::curvature(k, e_star) == Approx(shifted.pitch_curvature(m)).epsilon(1e-14));
        }
        // On the dwell the roller centre stays r_b + r_r from the cam centre, the contact on r_b.
        const FollowerMotion dwell = linear_program.evaluate(10 * deg);
        CHECK(std::hypot(e_star, TranslatingRoller::kinematics_from(dwell, s0_star, e_star).R) ==
              Approx(rp).epsilon(1e-15));
        CHECK(shifted.profile(10 * deg, dwell).surface.norm() == Approx(rb).epsilon(1e-14));
    }
    // A larger offset steepens the return.
    CHECK(std::abs(max_pressure_angle(linear_program, TranslatingRoller(rb, rr, 0.010 + de)).value) >
          std::abs(max_pressure_angle(linear_program, TranslatingRoller(rb, rr, 0.010)).value));
}

TEST_CASE("translating roller: the profile closes after a revolution; its CSV in metres starts on the base circle") {
    const TranslatingRoller roller(0.030, 0.008, 0.010);
    const FollowerProfilePoint first = roller.profile(0.0, linear_program.evaluate(0.0));
    const FollowerProfilePoint last = roller.profile(2 * pi, linear_program.evaluate(2 * pi));
    CHECK((first.surface - last.surface).norm() < 1e-15);
    CHECK((first.reference - last.reference).norm() < 1e-15);
    const std::string path = "followers_test_cam.csv";
    write_cam_csv(path, roller, linear_program, 360, std::nullopt, LengthUnit::m);
    std::ifstream in(path);
    std::string line, header;
    std::vector<Vec> rows;
    while (std::getline(in, line)) {
        if (line.rfind("#", 0) == 0) continue;
        if (header.empty()) {
            header = line;
            continue;
        }
        double t, x, y;
        REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &x, &y) == 3);
        rows.emplace_back(x, y);
    }
    in.close();
    std::remove(path.c_str());
    CHECK(header == "theta_rad,surface_x_m,surface_y_m");
    REQUIRE(rows.size() == 360);
    // The first row is the contact on the base circle at theta = 0, which theta = 2 pi returns to.
    CHECK(rows.front().norm() == Approx(0.030).epsilon(1e-12));
    CHECK((rows.front() - last.surface).norm() < 1e-15);
    CHECK(
        (rows.back() - roller.profile(2 * pi * 359 / 360, linear_program.evaluate(2 * pi * 359 / 360)).surface).norm() <
        1e-15);
}

TEST_CASE(
    "translating roller: a dent narrower than a segment's sampling step sets the pressure angle and surface radius") {
    // A dent 0.1 deg wide centred at 100.125 deg on the 150 deg rise of the paper program: a search with
    // 600 samples per segment looks every 0.25 deg (100.0, 100.25 deg), on both sides of the dent. (A
    // deep one that undercuts is refused: profile_error.test.cpp.) 0.2 um deep under a 1 mm roller: no
    // undercut, but the dent's flank steepens the pressure angle and its convex edge is the tightest
    // spot of the cam.
    const MotionProgram healthy = MotionProgram::paper_default();
    const double c = 100.125 * deg, w = 0.1 * deg;
    const double rr = 0.001, rp = 0.040 + rr;
    // Zero-offset roller: pitch curve (R cos t, R sin t), R = r_b + r_r + h, written out here:
    // kappa = (R^2 + 2 R'^2 - R R'') / (R^2 + R'^2)^(3/2), alpha = atan(R' / R).
    const auto kappa_at = [&](const MotionProgram& p, double t) {
        const FollowerMotion m = p.evaluate(t);
        const double R = rp + m.h, dR = m.dh, d2R = m.d2h;
        return (R * R + 2 * dR * dR - R * d2R) / std::pow(R * R + dR * dR, 1.5);
    };
    const auto alpha_at = [&](const MotionProgram& p, double t) {
        const FollowerMotion m = p.evaluate(t);
        return std::atan2(m.dh, rp + m.h);
    };
    const MotionProgram shallow = healthy.with_profile_error(ProfileError::dent(c, w, 0.2e-6));
    const TranslatingRoller roller(0.040, rr, 0.0);
    // Truth: dense sampling of the formulas, 1e-3 deg over the revolution and 5e-7 deg across the dent.
    double alpha = 0, alpha_healthy = 0, kappa = 0;
    const auto visit = [&](double t) {
        alpha = std::max(alpha, std::abs(alpha_at(shallow, t)));
        alpha_healthy = std::max(alpha_healthy, std::abs(alpha_at(healthy, t)));
        kappa = std::max(kappa, kappa_at(shallow, t));
    };
    for (int k = 0; k < 360000; ++k) visit(k * 1e-3 * deg);
    for (int k = 0; k <= 220000; ++k) visit(c - 0.055 * deg + k * 5e-7 * deg);
    REQUIRE(alpha > alpha_healthy + 0.005);  // the dent matters
    REQUIRE(1.0 / kappa > rr);               // and does not undercut
    CHECK_NOTHROW(check_undercut(shallow, roller));
    const AngleExtremum steepest = max_pressure_angle(shallow, roller);
    CHECK(std::abs(steepest.value) == Approx(alpha).epsilon(1e-9));
    CHECK(std::abs(steepest.theta - c) < w / 2);
    const AngleExtremum tight = min_surface_radius(shallow, roller);
    CHECK(tight.value == Approx(1.0 / kappa - rr).epsilon(1e-6));
    CHECK(std::abs(tight.theta - c) < w / 2);
}

// ---------------------------------------------------------------------------------------------------
TEST_CASE("bad parameters are refused with the parameter named") {
    using Catch::Contains;
    CHECK_THROWS_WITH(TranslatingRoller(0.0, 0.008, 0.0), Contains("base_radius must be finite and > 0"));
    CHECK_THROWS_WITH(TranslatingRoller(0.030, -0.008, 0.0), Contains("roller_radius must be finite and > 0"));
    CHECK_THROWS_WITH(TranslatingRoller(NAN, 0.008, 0.0), Contains("base_radius"));
    CHECK_THROWS_WITH(TranslatingRoller(0.030, 0.008, NAN), Contains("offset"));
    CHECK_THROWS_WITH(TranslatingRoller(0.030, 0.008, 0.038), Contains("|offset| < base_radius + roller_radius"));

    CHECK_THROWS_WITH(TranslatingFlat(-0.035), Contains("base_radius must be finite and > 0"));
    CHECK_THROWS_WITH(TranslatingFlat(0.035, 90 * deg), Contains("|face_angle| < pi/2 rad (90 deg)"));
    CHECK_THROWS_WITH(TranslatingFlat(0.035, -pi / 2 - 0.1), Contains("face_angle"));
    CHECK_THROWS_WITH(TranslatingFlat(0.035, NAN), Contains("face_angle"));
    CHECK_THROWS_WITH(TranslatingFlat(0.035, 0.0, INFINITY), Contains("offset"));

    CHECK_THROWS_WITH(OscillatingRoller(0.0, 0.008, pivot, 0.06), Contains("base_radius must be finite and > 0"));
    CHECK_THROWS_WITH(OscillatingRoller(0.035, NAN, pivot, 0.06), Contains("roller_radius must be finite and > 0"));
    CHECK_THROWS_WITH(OscillatingRoller(0.035, 0.008, pivot, -0.06), Contains("arm_length must be finite and > 0"));
    CHECK_THROWS_WITH(OscillatingRoller(0.035, 0.008, Vec(NAN, 0.04), 0.06), Contains("pivot must be finite"));
    CHECK_THROWS_WITH(OscillatingRoller(0.035, 0.008, Vec(0.02, 0.02), 0.03),
                      Contains("pivot must lie outside the base circle"));
    // |pivot| = 80.6 mm, r_b + r_r = 43 mm: the arm must lie in (37.6, 123.6) mm.
    CHECK_THROWS_WITH(OscillatingRoller(0.035, 0.008, pivot, 0.030), Contains("arm_length must lie in (0.0376"));
    CHECK_THROWS_WITH(OscillatingRoller(0.035, 0.008, pivot, 0.130), Contains("arm_length must lie in"));
    CHECK_THROWS_WITH(OscillatingRoller(0.035, 0.008, pivot, 0.06, static_cast<ArmTurn>(7)), Contains("turn must be"));

    CHECK_THROWS_WITH(OscillatingFlat(0.0, pivot), Contains("base_radius must be finite and > 0"));
    CHECK_THROWS_WITH(OscillatingFlat(0.035, Vec(0.07, INFINITY)), Contains("pivot must be finite"));
    CHECK_THROWS_WITH(OscillatingFlat(0.035, Vec(0.01, 0.0)), Contains("pivot must lie outside the base circle"));
    CHECK_THROWS_WITH(OscillatingFlat(0.035, pivot, NAN), Contains("face_offset"));
    CHECK_THROWS_WITH(OscillatingFlat(0.035, pivot, -0.05), Contains("face_offset = -0.05 m: the face cannot touch"));
}

TEST_CASE("check_undercut: an undercutting roller and a cusped flat face are refused, theta named") {
    // 40 mm cycloidal rise over 40 deg (steep) with a 12 mm roller on a 10 mm base circle.
    const TranslatingRoller big_roller(0.010, 0.012, 0.0);
    const std::string undercut = message_of([&] { check_undercut(steep, big_roller); });
    CHECK_THAT(undercut, Catch::Contains("undercuts at theta = ") && Catch::Contains("roller_radius = 0.012 m"));
    // The named angle is where the pitch curve is tightest: its curvature in closed form (paper eqs
    // 2-5 with e = 0, R = r_b + r_r + h), sampled every 1e-3 deg, then every 1e-7 deg around the best.
    const auto kappa = [](double theta) {
        const FollowerMotion m = steep.evaluate(theta);
        const double R = 0.022 + m.h;
        return (R * R + 2 * m.dh * m.dh - R * m.d2h) / std::pow(R * R + m.dh * m.dh, 1.5);
    };
    double tightest = -std::numeric_limits<double>::infinity(), tightest_at = 0;
    for (int k = 0; k < 360000; ++k)
        if (kappa(k * 1e-3 * deg) > tightest) tightest = kappa(k * 1e-3 * deg), tightest_at = k * 1e-3 * deg;
    const double coarse = tightest_at;
    for (int k = -10000; k <= 10000; ++k)
        if (kappa(coarse + k * 1e-7 * deg) > tightest)
            tightest = kappa(coarse + k * 1e-7 * deg), tightest_at = coarse + k * 1e-7 * deg;
    REQUIRE(1.0 / tightest < 0.012);  // the roller cannot trace it
    CHECK(theta_in(undercut) == Approx(tightest_at / deg).margin(1e-5));
    // The same small cam with a 50 mm arm swinging 0.5 rad (25 mm at the roller) in 40 deg.
    CHECK_THROWS_WITH(check_undercut(steep_swing, OscillatingRoller(0.010, 0.012, Vec(0.05, 0.03), 0.05)),
                      Catch::Contains("undercuts at theta = "));

    // 10 mm cycloidal rise over 60 deg (fast) on a 10 mm base circle: r_b + h + h'' < 0 on the rise.
    double worst = 1, at = 0;
    for (int k = 0; k < 360000; ++k) {
        const FollowerMotion m = fast.evaluate(k * 1e-3 * deg);
        if (0.010 + m.h + m.d2h < worst) worst = 0.010 + m.h + m.d2h, at = k * 1e-3;
    }
    REQUIRE(worst < 0);
    const std::string cusp = message_of([&] { check_undercut(fast, TranslatingFlat(0.010)); });
    CHECK_THAT(cusp, Catch::Contains("cusp at theta = ") && Catch::Contains("must be > 0"));
    CHECK(theta_in(cusp) == Approx(at).margin(2e-3));
    CHECK_NOTHROW(check_undercut(fast, TranslatingFlat(0.060)));

    // An oscillating face whose arm swings faster than the cam turns (whip: w = sigma s' - 1 crosses 0).
    CHECK_THROWS_WITH(check_undercut(whip, OscillatingFlat(0.035, pivot)), Catch::Contains("theta = "));
}

namespace {
// A follower whose curvature is NaN on part of the rise, or everywhere.
struct NanFollower {
    bool everywhere;
    double follower_radius() const { return 0.008; }
    FollowerProfilePoint profile(double theta, const FollowerMotion&) const {
        const bool bad = everywhere || (theta > 100 * deg && theta < 100.6 * deg);
        const double r = bad ? std::numeric_limits<double>::quiet_NaN() : 0.02;
        return {theta, Vec::Zero(), Vec::Zero(), Vec::Zero(), r, r, 0.1};
    }
};
struct NanAngleFollower {
    double follower_radius() const { return std::numeric_limits<double>::infinity(); }
    FollowerProfilePoint profile(double theta, const FollowerMotion&) const {
        const double a = theta > 250 * deg && theta < 250.6 * deg ? std::numeric_limits<double>::quiet_NaN() : 0.1;
        return {theta, Vec::Zero(), Vec::Zero(), Vec::Zero(), 0.02, 0.02, a};
    }
};
}  // namespace

TEST_CASE("check_undercut: a NaN curvature or pressure angle fails the check") {
    const std::string partial = message_of([] { check_undercut(linear_program, NanFollower{false}); });
    CHECK_THAT(partial, Catch::Contains("not finite at theta = "));
    CHECK(theta_in(partial) > 100.0);
    CHECK(theta_in(partial) < 100.6);
    CHECK_THROWS_WITH(check_undercut(linear_program, NanFollower{true}), Catch::Contains("not finite at theta = "));
    CHECK_THROWS_WITH(check_undercut(linear_program, NanAngleFollower{}),
                      Catch::Contains("pressure angle is not finite"));
    CHECK_THROWS_WITH(min_surface_radius(linear_program, NanFollower{false}), Catch::Contains("theta = "));
}
