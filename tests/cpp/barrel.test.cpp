// SPDX-License-Identifier: BSD-3-Clause
// Barrel cams' followers: the contact normal against the sampled developed pitch curve, its rates and
// the lever's against central differences, the pitch curvature against the circle through three
// neighbouring pitch points, the closed form tan(alpha) = h'/rho, and the builder's and exports'
// refusals. The exact groove walls are checked against a brute-force envelope in
// tests/python/test_barrel_cam.py.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "camfollower/geometry/barrel_groove.hpp"
#include "camfollower/geometry/export.hpp"
#include "camfollower/model/mechanism_builder.hpp"

using namespace camfollower;

namespace {

MotionProgram transfer(double lift) {
    return MotionProgram({{MotionLaw::dwell(), 0.0, 0.7, 0.0, 0.0},
                          {MotionLaw::modified_sine(), 0.7, 3.0, 0.0, lift},
                          {MotionLaw::dwell(), 3.0, 3.8, lift, lift},
                          {MotionLaw::cycloidal(), 3.8, two_pi, lift, 0.0}});
}

// The circle through three points: 1 / radius, signed > 0 when they turn clockwise (convex, as the
// followers' curvature is signed).
double three_point_curvature(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double cross = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return -2.0 * cross / ((b - a).norm() * (c - b).norm() * (c - a).norm());
}

template <class F>
void check_against_the_pitch_curve(const F& f, const MotionProgram& p) {
    const double eps = 1e-5;
    for (double theta = 0.05; theta < two_pi - 0.05; theta += 0.1) {
        INFO("theta = " << theta);
        const FollowerProfilePoint a = f.profile(theta - eps, p.evaluate(theta - eps));
        const FollowerProfilePoint b = f.profile(theta, p.evaluate(theta));
        const FollowerProfilePoint c = f.profile(theta + eps, p.evaluate(theta + eps));
        const Eigen::Vector2d tangent = (c.reference - a.reference).normalized();
        const ContactGeometry g = f.contact(theta, p.evaluate(theta));
        // The normal is perpendicular to the pitch curve and points to the roller's side (+y lifts).
        CHECK(std::abs(g.normal.dot(tangent)) < 1e-8);
        CHECK((b.reference - b.surface).normalized().isApprox(g.normal, 1e-12));
        const ContactGeometry gm = f.contact(theta - eps, p.evaluate(theta - eps));
        const ContactGeometry gp = f.contact(theta + eps, p.evaluate(theta + eps));
        CHECK((g.dnormal - (gp.normal - gm.normal) / (2 * eps)).norm() < 1e-6 * (1.0 + g.dnormal.norm()));
        CHECK(g.dlever == Approx((gp.lever - gm.lever) / (2 * eps)).margin(1e-7));
        // Points 1e-3 rad apart: the circle's truncation error ~1e-6 relative, its rounding far below.
        const double wide = 1e-3, kappa = f.pitch_curvature(p.evaluate(theta));
        const Eigen::Vector2d before = f.profile(theta - wide, p.evaluate(theta - wide)).reference;
        const Eigen::Vector2d after = f.profile(theta + wide, p.evaluate(theta + wide)).reference;
        CHECK(kappa == Approx(three_point_curvature(before, b.reference, after)).epsilon(1e-5).margin(1e-6));
    }
}

}  // namespace

TEST_CASE("barrel roller: tan(alpha) = h'/rho, lever cos(alpha), the developed pitch curve's normal") {
    const MotionProgram p = transfer(0.04);
    const BarrelRoller f(0.06, 0.016, 0.01);
    CHECK(f.pitch_radius() == Approx(0.052).epsilon(1e-15));
    for (double theta = 0.0; theta < two_pi; theta += 0.05) {
        const FollowerMotion m = p.evaluate(theta);
        const ContactGeometry g = f.contact(theta, m);
        CHECK(g.pressure_angle() == Approx(std::atan(m.dh / 0.052)).margin(1e-14));
        CHECK(g.lever == Approx(0.052 / std::hypot(0.052, m.dh)).margin(1e-15));
        // The developed cam frame slides by rho theta: the roller centre sits at (rho theta, h).
        CHECK(f.profile(theta, m).reference.isApprox(Eigen::Vector2d(0.052 * theta, m.h), 1e-15));
    }
    check_against_the_pitch_curve(f, p);
}

TEST_CASE("barrel swing arm: normal, rates and curvature against the sampled pitch curve") {
    const MotionProgram p = transfer(0.35);  // rad
    const double L = 0.12, b = 0.17;
    for (ArmTurn turn : {ArmTurn::counter_clockwise, ArmTurn::clockwise}) {
        const double sigma = turn_sign(turn);
        // The arm starts b before the perpendicular to the cam axis, on the side it lifts away from.
        const BarrelArmRoller f(0.06, 0.016, 0.01, Eigen::Vector2d(-sigma * L * std::cos(b), L * std::sin(b)), L, turn);
        const RollerPath start = f.roller_path(p.evaluate(0.0));
        CHECK(std::abs(start.centre.x()) < 1e-15);
        CHECK(std::abs(start.centre.y()) < 1e-15);
        CHECK(f.lifting_direction(p.evaluate(0.0)).y() > 0.9);
        check_against_the_pitch_curve(f, p);
    }
}

TEST_CASE("barrel cams: bad geometry, disk-only features and shafts without axial DOFs are refused") {
    CHECK_THROWS_WITH(BarrelRoller(0.06, 0.06, 0.01), Catch::Contains("groove_depth = 0.06 m must be below"));
    CHECK_THROWS_WITH(BarrelRoller(0.06, 0.01, 0.0), Catch::Contains("roller_radius"));
    CHECK_THROWS_WITH(BarrelArmRoller(0.06, 0.016, 0.01, Eigen::Vector2d(0.0, 0.01), 0.1),
                      Catch::Contains("pivot x must not be 0"));
    const MotionProgram p = transfer(0.04);
    const BarrelRoller f(0.06, 0.016, 0.01);
    CHECK_THROWS_WITH(cam_outline(Follower(f), p), Catch::Contains("has no disk outline"));
    CHECK_THROWS_WITH(barrel_groove(f, p, 360, -1e-4), Catch::Contains("groove clearance"));
    CHECK_THROWS_WITH(barrel_groove(f, p, 360, 0.02), Catch::Contains("must be below the roller radius"));

    MechanismBuilder b;
    b.add_dof("w", 1.0);
    b.add_shaft({"shaft", BeamSection::hollow_circle(0.03, 0.0, 210e9, 0.3, 7850.0), 0.3, 0.0, {0.15}, false, 0.0});
    ContactPairSpec c{"cam", p, f, {1e9, 1.0, 0.0}, 0.0, ground_name, ground_name, "w", ground_name, CamEccentricity{}};
    CHECK_THROWS_WITH(b.mount_cam(c, "shaft", 0.15), Catch::Contains("needs its axial DOFs (axial = true)"));
    ContactPairSpec eccentric = c;
    eccentric.eccentricity.radius = 1e-4;
    CHECK_THROWS_WITH(ContactPair(eccentric, -1, -1, 0, -1), Catch::Contains("eccentricity is modelled for disk cams"));
    CHECK_NOTHROW(ContactPair(c, -1, -1, 0, -1));
}
