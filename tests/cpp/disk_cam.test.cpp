// SPDX-License-Identifier: BSD-3-Clause
// Disk cam kinematics: closed form (paper eqs 2-5) against a purely numerical envelope of roller
// circles, curvature against finite differences of the sampled curves, closure, errors, CSV export.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "camfollower/geometry/disk_cam.hpp"

using namespace camfollower;

namespace {
const double deg = pi / 180.0;

// Pitch point (roller centre) in the cam frame, written out from its definition: the roller centre
// sits at axial distance R = s0 + h, lateral e, and the cam frame is the follower frame turned by theta.
Eigen::Vector2d pitch_point(const DiskCam& cam, double theta, double e) {
    const auto& g = cam.geometry();
    const double rp = g.base_radius + g.roller_radius;
    const double R = std::sqrt(rp * rp - e * e) + cam.program().evaluate(theta).h;
    return {R * std::cos(theta) - e * std::sin(theta), R * std::sin(theta) + e * std::cos(theta)};
}

// Envelope point from the intersection of the roller circles at theta -+ eta (the cam-side one),
// Richardson-extrapolated in eta^2. Uses positions only: no derivative, no pressure angle.
Eigen::Vector2d envelope_point(const DiskCam& cam, double theta, double e) {
    const double r = cam.geometry().roller_radius;
    auto intersect = [&](double eta) {
        const Eigen::Vector2d p1 = pitch_point(cam, theta - eta, e), p2 = pitch_point(cam, theta + eta, e);
        const Eigen::Vector2d chord = p2 - p1, mid = 0.5 * (p1 + p2);
        const double half = 0.5 * chord.norm();
        const Eigen::Vector2d inward(-chord.y() / chord.norm(), chord.x() / chord.norm());
        return Eigen::Vector2d(mid + std::sqrt(r * r - half * half) * inward);
    };
    const double eta = 2e-3;
    return (4.0 * intersect(eta / 2) - intersect(eta)) / 3.0;
}

DiskCam aggressive_cam(double offset) {
    // 20 mm cycloidal rise over 100 deg on a small base circle: strong curvature, concave flanks.
    const MotionProgram p({{MotionLaw::cycloidal(), 0, 100 * deg, 0, 0.02},
                           {MotionLaw::dwell(), 100 * deg, 160 * deg, 0.02, 0.02},
                           {MotionLaw::polynomial_345(), 160 * deg, 2 * pi, 0.02, 0.0}});
    return DiskCam({0.025, 0.006, offset}, p);
}
}  // namespace

TEST_CASE("base circle: on the dwell the surface is the base circle and alpha = atan(-e/s0)") {
    const DiskCam cam = DiskCam::paper_default();
    const double s0 = std::sqrt(0.038 * 0.038 - 0.01 * 0.01);
    for (double t : {5 * deg, 20 * deg}) {
        const ProfilePoint p = cam.profile(t);
        CHECK(p.kinematics.R == Approx(s0).epsilon(1e-15));
        CHECK(p.surface.norm() == Approx(0.030).epsilon(1e-14));
        CHECK(p.pitch.norm() == Approx(0.038).epsilon(1e-14));
        CHECK(p.kinematics.pressure_angle() == Approx(std::atan(-0.01 / s0)).epsilon(1e-14));
        CHECK(p.surface_radius == Approx(0.030).epsilon(1e-12));
    }
}

TEST_CASE("closed-form profile matches a numerical envelope of roller circles") {
    for (const DiskCam& cam : {DiskCam::paper_default(), aggressive_cam(0.008), aggressive_cam(-0.005)}) {
        const double e = cam.geometry().offset;
        INFO("offset " << e);
        double worst_mm = 0.0, worst_alpha_deg = 0.0;
        for (int k = 0; k < 720; ++k) {
            const double t = (k + 0.41) * 0.5 * deg;
            const ProfilePoint p = cam.profile(t);
            const Eigen::Vector2d env = envelope_point(cam, t, e);
            worst_mm = std::max(worst_mm, 1e3 * (p.surface - env).norm());
            // Pressure angle of the envelope: normal (pitch - envelope) turned back into the
            // follower frame is (cos a, -sin a) in (axial, lateral).
            const Eigen::Vector2d n = pitch_point(cam, t, e) - env;
            const double axial = std::cos(t) * n.x() + std::sin(t) * n.y();
            const double lateral = -std::sin(t) * n.x() + std::cos(t) * n.y();
            const double alpha_env = std::atan2(-lateral, axial);
            worst_alpha_deg = std::max(worst_alpha_deg, std::abs(alpha_env - p.kinematics.pressure_angle()) / deg);
        }
        CHECK(worst_mm < 1e-6);
        CHECK(worst_alpha_deg < 1e-3);
    }
}

TEST_CASE("curvature of pitch and surface curves against finite differences of the points") {
    const DiskCam cam = aggressive_cam(0.008);
    const double h = 1e-4;
    auto curvature = [&](auto point, double t) {
        const Eigen::Vector2d a = point(t - h), b = point(t), c = point(t + h);
        const Eigen::Vector2d d1 = (c - a) / (2 * h), d2 = (c - 2 * b + a) / (h * h);
        return (d1.x() * d2.y() - d1.y() * d2.x()) / std::pow(d1.norm(), 3);
    };
    for (int k = 0; k < 360; ++k) {
        const double t = (k + 0.5) * deg;
        const ProfilePoint p = cam.profile(t);
        const double k_pitch = curvature([&](double s) { return cam.profile(s).pitch; }, t);
        const double k_surf = curvature([&](double s) { return cam.profile(s).surface; }, t);
        INFO("theta = " << t / deg);
        CHECK(p.pitch_curvature == Approx(k_pitch).epsilon(1e-5).margin(1e-3));
        CHECK(1.0 / p.surface_radius == Approx(k_surf).epsilon(1e-5).margin(1e-3));
    }
}

TEST_CASE("pressure-angle derivative against finite differences") {
    const DiskCam cam = DiskCam::paper_default();
    for (int k = 0; k < 360; ++k) {
        const double t = (k + 0.5) * deg, h = 1e-6;
        const double fd = (cam.kinematics(t + h).pressure_angle() - cam.kinematics(t - h).pressure_angle()) / (2 * h);
        CHECK(cam.kinematics(t).dalpha == Approx(fd).margin(1e-7));
    }
}

TEST_CASE("extremes of the paper cam: located on the right segment, consistent with sampling") {
    const DiskCam cam = DiskCam::paper_default();
    const AngleExtremum rise = cam.max_pressure_angle_rise();
    const AngleExtremum ret = cam.max_pressure_angle_return();
    CHECK(rise.theta >= 30 * deg);
    CHECK(rise.theta <= 180 * deg);
    CHECK(ret.theta >= 210 * deg);
    CHECK(ret.value < 0.0);
    // e = 10 mm exceeds the peak R' = 2 h_max / beta = 7.6 mm/rad: alpha < 0 all along the rise, its
    // magnitude largest where the rise leaves the base circle, atan(-e / s0).
    CHECK(rise.value == Approx(std::atan(-0.01 / std::sqrt(0.038 * 0.038 - 1e-4))).epsilon(1e-12));
    // A positive offset raises the return magnitude above the rise's.
    CHECK(std::abs(ret.value) > std::abs(rise.value));
    double sampled_rise = 0, sampled_ret = 0;
    for (int k = 0; k <= 360000; ++k) {
        const double t = k * 1e-3 * deg, a = cam.kinematics(t).pressure_angle();
        if (t >= 30 * deg && t <= 180 * deg) sampled_rise = std::max(sampled_rise, std::abs(a));
        if (t >= 210 * deg) sampled_ret = std::max(sampled_ret, std::abs(a));
    }
    CHECK(std::abs(rise.value) == Approx(sampled_rise).epsilon(1e-9));
    CHECK(std::abs(ret.value) == Approx(sampled_ret).epsilon(1e-9));
    const AngleExtremum rho = cam.min_surface_radius();
    double sampled_rho = 1;
    for (int k = 0; k < 36000; ++k) {
        const ProfilePoint p = cam.profile(k * 0.01 * deg);
        if (p.surface_radius > 0) sampled_rho = std::min(sampled_rho, p.surface_radius);
    }
    CHECK(rho.value == Approx(sampled_rho).epsilon(1e-7));
    CHECK(rho.value == Approx(0.030).epsilon(1e-12));  // the base circle is the tightest spot here
    const AngleExtremum flank = cam.min_surface_radius(0.010, true);
    double sampled_flank = 1;
    for (int k = 0; k < 36000; ++k) {
        const double t = k * 0.01 * deg;
        if ((t >= 30 * deg - 1e-9 && t <= 180 * deg + 1e-9) || t >= 210 * deg - 1e-9)
            sampled_flank = std::min(sampled_flank, cam.profile(t).surface_radius);
    }
    CHECK(flank.value == Approx(sampled_flank).epsilon(1e-7));
}

TEST_CASE("perturbed offset: same as a cam built with that offset, base circle unchanged") {
    const DiskCam cam = DiskCam::paper_default();
    const double de = 10e-6;
    const DiskCam shifted({0.030, 0.008, 0.010 + de}, MotionProgram::paper_default());
    for (double t : {10 * deg, 70 * deg, 250 * deg}) {
        const ProfilePoint a = cam.profile(t, 0.010 + de), b = shifted.profile(t);
        CHECK((a.surface - b.surface).norm() < 1e-15);
        CHECK(a.kinematics.pressure_angle() == b.kinematics.pressure_angle());
    }
    const double rp = 0.038, e_star = 0.010 - de;
    CHECK(cam.profile(10 * deg, e_star).kinematics.R == Approx(std::sqrt(rp * rp - e_star * e_star)).epsilon(1e-15));
    CHECK(std::abs(cam.max_pressure_angle_rise(0.010 + de).value) > std::abs(cam.max_pressure_angle_rise().value));
}

TEST_CASE("the sampled profile closes: first point = last point") {
    const auto pts = DiskCam::paper_default().sample(720);
    REQUIRE(pts.size() == 721);
    CHECK((pts.front().surface - pts.back().surface).norm() < 1e-15);
    CHECK((pts.front().pitch - pts.back().pitch).norm() < 1e-15);
}

TEST_CASE("CSV export writes a closed point list in metres") {
    const std::string path = "disk_cam_test_surface.csv";
    DiskCam::paper_default().write_surface_csv(path, 360);
    std::ifstream in(path);
    std::string header, line, first, last;
    std::getline(in, header);
    CHECK(header == "theta_rad,x_m,y_m");
    int rows = 0;
    while (std::getline(in, line)) {
        if (rows == 0) first = line;
        last = line, ++rows;
    }
    CHECK(rows == 361);
    const auto xy = [](const std::string& s) { return s.substr(s.find(',') + 1); };
    double x0, y0, x1, y1;
    std::sscanf(xy(first).c_str(), "%lf,%lf", &x0, &y0);
    std::sscanf(xy(last).c_str(), "%lf,%lf", &x1, &y1);
    CHECK(std::hypot(x0 - x1, y0 - y1) < 1e-15);
    CHECK(std::hypot(x0, y0) == Approx(0.030).epsilon(1e-12));
    std::remove(path.c_str());
    CHECK_THROWS_WITH(DiskCam::paper_default().write_surface_csv("/nonexistent-dir/x.csv"),
                      Catch::Contains("path: cannot create a temporary file in '/nonexistent-dir'"));
}

TEST_CASE("bad geometry is rejected with the parameter and range named") {
    const MotionProgram p = MotionProgram::paper_default();
    CHECK_THROWS_WITH(DiskCam({0.030, 0.008, 0.038}, p), Catch::Contains("|offset| < base_radius + roller_radius"));
    CHECK_THROWS_WITH(DiskCam({0.030, 0.0, 0.01}, p), Catch::Contains("roller_radius must be finite and > 0"));
    CHECK_THROWS_WITH(DiskCam({-0.030, 0.008, 0.01}, p), Catch::Contains("base_radius"));
    CHECK_THROWS_WITH(DiskCam({0.030, 0.008, NAN}, p), Catch::Contains("offset"));
    // A 40 mm rise over 40 deg with a big roller on a small cam cannot be followed.
    const MotionProgram steep({{MotionLaw::cycloidal(), 0, 40 * deg, 0, 0.04},
                               {MotionLaw::cycloidal(), 40 * deg, 2 * pi, 0.04, 0.0}});
    CHECK_THROWS_WITH(DiskCam({0.010, 0.012, 0.0}, steep), Catch::Contains("undercuts"));
    CHECK_THROWS_WITH(DiskCam::paper_default().profile(0.1, 0.05), Catch::Contains("offset"));
}

TEST_CASE("a dent narrower than a segment's sampling step is found: undercut, pressure angle, surface radius") {
    // Dents 0.1 deg wide centred at 100.125 deg on the 150 deg rise of the paper program: a search with
    // 600 samples per segment looks every 0.25 deg (100.0, 100.25 deg), on both sides of the dent.
    const MotionProgram healthy = MotionProgram::paper_default();
    const double c = 100.125 * deg, w = 0.1 * deg;
    // Zero-offset roller: pitch curve (R cos t, R sin t), R = r_b + r_r + h, written out here:
    // kappa = (R^2 + 2 R'^2 - R R'') / (R^2 + R'^2)^(3/2), alpha = atan(R' / R).
    const auto kappa_at = [](const MotionProgram& p, double rp, double t) {
        const FollowerMotion m = p.evaluate(t);
        const double R = rp + m.h, dR = m.dh, d2R = m.d2h;
        return (R * R + 2 * dR * dR - R * d2R) / std::pow(R * R + dR * dR, 1.5);
    };
    const auto alpha_at = [](const MotionProgram& p, double rp, double t) {
        const FollowerMotion m = p.evaluate(t);
        return std::atan2(m.dh, rp + m.h);
    };

    // 1 um deep: where the dent is most convex (x^2 = 3/7 of its half width) the pitch curve's radius
    // is far below a 12.5 mm roller: the cam undercuts there, and DiskCam must refuse it.
    const MotionProgram deep = healthy.with_profile_error(ProfileError::dent(c, w, 1e-6));
    const double x = std::sqrt(3.0 / 7);
    REQUIRE(1.0 / kappa_at(deep, 0.0525, c - x * w / 2) > 0.0);
    REQUIRE(1.0 / kappa_at(deep, 0.0525, c - x * w / 2) < 0.0125);
    std::string message = "(no exception)";
    try {
        DiskCam({0.040, 0.0125, 0.0}, deep);
    } catch (const std::invalid_argument& e) {
        message = e.what();
    }
    CHECK_THAT(message, Catch::Contains("undercuts at theta = "));
    if (message.find("theta = ") != std::string::npos)
        CHECK(std::abs(std::stod(message.substr(message.find("theta = ") + 8)) - 100.125) <= 0.05);
    CHECK_NOTHROW(DiskCam({0.040, 0.0125, 0.0}, healthy));

    // 0.2 um deep with a 1 mm roller: no undercut, but the dent's flank steepens the pressure angle and
    // its convex edge is the tightest spot of the cam. Truth: dense sampling of the formulas above,
    // 1e-3 deg over the rise and 5e-7 deg across the dent.
    const double rr = 0.001, rp = 0.040 + rr;
    const MotionProgram shallow = healthy.with_profile_error(ProfileError::dent(c, w, 0.2e-6));
    const DiskCam cam({0.040, rr, 0.0}, shallow);
    double alpha = 0, alpha_healthy = 0, kappa = 0;
    const auto visit = [&](double t) {
        alpha = std::max(alpha, std::abs(alpha_at(shallow, rp, t)));
        alpha_healthy = std::max(alpha_healthy, std::abs(alpha_at(healthy, rp, t)));
        kappa = std::max(kappa, kappa_at(shallow, rp, t));
    };
    for (int k = 0; k <= 150000; ++k) visit(30 * deg + k * 1e-3 * deg);
    for (int k = 0; k <= 220000; ++k) visit(c - 0.055 * deg + k * 5e-7 * deg);
    REQUIRE(alpha > alpha_healthy + 0.005);  // the dent matters
    REQUIRE(1.0 / kappa > rr);               // and does not undercut
    const AngleExtremum rise = cam.max_pressure_angle_rise();
    CHECK(rise.value == Approx(alpha).epsilon(1e-9));
    CHECK(std::abs(rise.theta - c) < w / 2);
    for (bool flanks_only : {false, true}) {
        const AngleExtremum tight = cam.min_surface_radius(0.0, flanks_only);
        CHECK(tight.value == Approx(1.0 / kappa - rr).epsilon(1e-6));
        CHECK(std::abs(tight.theta - c) < w / 2);
    }
}
