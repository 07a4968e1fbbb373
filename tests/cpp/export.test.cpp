// SPDX-License-Identifier: BSD-3-Clause
// The manufacturing export (geometry/export.hpp, detail/atomic_file.hpp) against independent truth:
// - the cutter path for r_c = r_r is the roller's pitch curve, written out here from its definition;
// - every cutter-path point lies r_c from the surface, by a brute-force nearest-point search over a
//   dense polyline of the surface;
// - the tightest concave radius that limits the cutter is found from three-point circles through the
//   exported surface points;
// - unit scaling, the header's statements (rotation sense checked by the rows' signed area, the zero
//   mark by the base circle), and the atomic writer's refusals and clean-up.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <dirent.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "angles.hpp"
#include "camfollower/geometry/export.hpp"

using namespace camfollower;
using Vec = Eigen::Vector2d;

namespace {
const MotionProgram paper = MotionProgram::paper_default(0.010);

// A fast cycloidal rise on a small cam: the surface is concave where the rise starts (R'' > R).
const MotionProgram concave_rise({{MotionLaw::dwell(), 0.0, 60 * deg, 0.0, 0.0},
                                  {MotionLaw::cycloidal(), 60 * deg, 120 * deg, 0.0, 0.010},
                                  {MotionLaw::dwell(), 120 * deg, 200 * deg, 0.010, 0.010},
                                  {MotionLaw::cycloidal(), 200 * deg, 2 * pi, 0.010, 0.0}});

// A fresh empty folder under /tmp, removed (with its files) at the end of the test.
struct TempDir {
    std::string path;
    TempDir() {
        char name[] = "/tmp/cf-export-test-XXXXXX";
        REQUIRE(::mkdtemp(name) != nullptr);
        path = name;
    }
    ~TempDir() {
        for (const std::string& f : entries()) {
            const std::string p = path + "/" + f;
            struct stat st {};
            if (::lstat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) ::rmdir(p.c_str());
            else ::unlink(p.c_str());
        }
        ::rmdir(path.c_str());
    }
    std::vector<std::string> entries() const {
        std::vector<std::string> out;
        if (DIR* d = ::opendir(path.c_str())) {
            while (const dirent* e = ::readdir(d)) {
                const std::string n = e->d_name;
                if (n != "." && n != "..") out.push_back(n);
            }
            ::closedir(d);
        }
        std::sort(out.begin(), out.end());
        return out;
    }
};

std::string read_all(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

double segment_distance(const Vec& p, const Vec& a, const Vec& b) {
    const Vec ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * ab)).norm();
}

// Nearest distance from p to the closed polyline through `curve`.
double distance_to_polyline(const Vec& p, const std::vector<Vec>& curve) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < curve.size(); ++k)
        best = std::min(best, segment_distance(p, curve[k], curve[(k + 1) % curve.size()]));
    return best;
}

// Signed radius of the circle through a, b, c (> 0 when a -> b -> c turns clockwise, i.e. convex for
// an outline run clockwise round the cam, as the export runs).
double three_point_radius(const Vec& a, const Vec& b, const Vec& c) {
    const double cross2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return -(b - a).norm() * (c - b).norm() * (c - a).norm() / (2.0 * cross2);
}

double signed_area(const std::vector<Vec>& v) {
    double a = 0.0;
    for (std::size_t k = 0; k < v.size(); ++k) {
        const Vec& p = v[k];
        const Vec& q = v[(k + 1) % v.size()];
        a += 0.5 * (p.x() * q.y() - p.y() * q.x());
    }
    return a;
}

double theta_in_message(const std::string& message) {
    const std::size_t at = message.find("theta = ");
    REQUIRE(at != std::string::npos);
    return std::atof(message.c_str() + at + 8);
}

}  // namespace

TEST_CASE("the cutter path of a cutter as large as the roller is the pitch curve") {
    SECTION("translating roller: pitch curve Rot(-theta) (e, s0 + h)") {
        const double rb = 0.030, rr = 0.008, e = 0.010;
        const TranslatingRoller f(rb, rr, e);
        const CamOutline o = cam_outline(f, paper, 720, rr, LengthUnit::m);
        REQUIRE(o.cutter.size() == 720);
        double worst = 0.0;
        for (std::size_t k = 0; k < o.theta.size(); ++k) {
            const double t = o.theta[k];
            const double R = std::sqrt((rb + rr) * (rb + rr) - e * e) + paper.evaluate(t).h;
            const Vec pitch(std::cos(t) * e + std::sin(t) * R, -std::sin(t) * e + std::cos(t) * R);
            worst = std::max(worst, (o.cutter[k] - pitch).norm());
        }
        CHECK(worst < 1e-15);
    }
    SECTION("oscillating roller, both arm senses: the roller centre") {
        for (ArmTurn turn : {ArmTurn::counter_clockwise, ArmTurn::clockwise}) {
            const OscillatingRoller f(0.030, 0.010, Vec(0.080, 0.020), 0.070, turn);
            const MotionProgram angular = MotionProgram::paper_default(15.0 * deg);
            const CamOutline o = cam_outline(f, angular, 720, 0.010, LengthUnit::mm);
            double worst = 0.0;
            for (std::size_t k = 0; k < o.theta.size(); ++k) {
                const double t = o.theta[k];
                const double phi = f.start_angle() + (turn == ArmTurn::clockwise ? -1 : 1) * angular.evaluate(t).h;
                const Vec centre_ground = Vec(0.080, 0.020) + 0.070 * Vec(std::cos(phi), std::sin(phi));
                const Vec centre(std::cos(t) * centre_ground.x() + std::sin(t) * centre_ground.y(),
                                 -std::sin(t) * centre_ground.x() + std::cos(t) * centre_ground.y());
                worst = std::max(worst, (o.cutter[k] - 1e3 * centre).norm());
            }
            CHECK(worst < 1e-12);  // mm
        }
    }
}

TEST_CASE("every cutter-path point lies one cutter radius from the surface (brute-force nearest point)") {
    struct Case {
        const char* name;
        Follower follower;
        const MotionProgram* program;
        double cutter;
    };
    const MotionProgram angular = MotionProgram::paper_default(15.0 * deg);
    const std::vector<Case> cases{
        {"translating roller, grinding wheel 25 mm", TranslatingRoller(0.030, 0.008, 0.010), &paper, 0.025},
        {"translating flat, end mill 6 mm", TranslatingFlat(0.030, 0.0, 0.0), &paper, 0.006},
        {"oscillating roller, 12 mm", OscillatingRoller(0.030, 0.010, Vec(0.080, 0.020), 0.070), &angular, 0.012},
        {"oscillating flat, 8 mm", OscillatingFlat(0.030, Vec(0.0, 0.080), 0.005), &angular, 0.008},
        {"concave cam, 3 mm cutter", TranslatingRoller(0.020, 0.005, 0.0), &concave_rise, 0.003},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const std::vector<Vec> dense = cam_outline(c.follower, *c.program, 20000, std::nullopt, LengthUnit::m).surface;
        const CamOutline o = cam_outline(c.follower, *c.program, 360, c.cutter, LengthUnit::m);
        double worst = 0.0;
        for (const Vec& p : o.cutter) worst = std::max(worst, std::abs(distance_to_polyline(p, dense) - c.cutter));
        // Chords of the dense polyline lie inside the convex surface by at most ~ (2 pi r / n)^2 / (8 rho).
        CHECK(worst < 2e-8);
    }
}

TEST_CASE("a cutter larger than the tightest concave radius is refused at that cam angle") {
    const TranslatingRoller f(0.020, 0.005, 0.0);
    // Truth: three-point circles through the exported surface points, concave ones only.
    const std::vector<Vec> s = cam_outline(f, concave_rise, 36000, std::nullopt, LengthUnit::m).surface;
    double tightest = std::numeric_limits<double>::infinity(), at = 0.0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double r = three_point_radius(s[(k + s.size() - 1) % s.size()], s[k], s[(k + 1) % s.size()]);
        if (r < 0.0 && -r < tightest)
            tightest = -r, at = 2 * pi * static_cast<double>(k) / static_cast<double>(s.size());
    }
    REQUIRE(std::isfinite(tightest));
    INFO("tightest concave radius " << tightest << " m at " << at / deg << " deg");
    CHECK(min_concave_radius(concave_rise, f).value == Approx(tightest).epsilon(1e-4));
    CHECK_NOTHROW(cam_outline(f, concave_rise, 360, 0.99 * tightest));
    try {
        cam_outline(f, concave_rise, 360, 1.01 * tightest);
        FAIL("a too large cutter was accepted");
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        CHECK_THAT(m, Catch::Contains("cutter_radius") && Catch::Contains("concave"));
        CHECK(theta_in_message(m) == Approx(at / deg).margin(0.05));
    }
    // A convex cam takes any cutter.
    CHECK(std::isinf(min_concave_radius(paper, TranslatingFlat(0.030)).value));
    CHECK_NOTHROW(cam_outline(TranslatingFlat(0.030), paper, 36, 0.5));
}

TEST_CASE("bad export input names the parameter") {
    const TranslatingRoller f(0.030, 0.008, 0.010);
    CHECK_THROWS_WITH(cam_outline(f, paper, 2), Catch::Contains("points must be an integer in [3, 10000000], got 2"));
    CHECK_THROWS_WITH(cam_outline(f, paper, 36, -0.001), Catch::Contains("cutter_radius must be finite and >= 0"));
    CHECK_THROWS_WITH(cam_outline(f, paper, 36, std::nan("")), Catch::Contains("cutter_radius"));
    CHECK_THROWS_WITH(length_unit_from_name("cm"), Catch::Contains("unit must be one of m, mm, um, inch"));
    // A roller that undercuts cannot be exported at all.
    const MotionProgram steep(
        {{MotionLaw::cycloidal(), 0, 40 * deg, 0, 0.04}, {MotionLaw::cycloidal(), 40 * deg, 2 * pi, 0.04, 0.0}});
    CHECK_THROWS_WITH(cam_outline(TranslatingRoller(0.010, 0.012, 0.0), steep), Catch::Contains("undercuts"));
}

TEST_CASE("units scale every point by the unit's length") {
    const OscillatingRoller f(0.030, 0.010, Vec(0.080, 0.020), 0.070);
    const MotionProgram angular = MotionProgram::paper_default(15.0 * deg);
    const CamOutline m = cam_outline(f, angular, 90, 0.004, LengthUnit::m);
    const CamOutline mm = cam_outline(f, angular, 90, 0.004, LengthUnit::mm);
    const CamOutline um = cam_outline(f, angular, 90, 0.004, LengthUnit::um);
    const CamOutline in = cam_outline(f, angular, 90, 0.004, LengthUnit::inch);
    for (std::size_t k = 0; k < m.theta.size(); ++k) {
        CHECK((mm.surface[k] - 1000.0 * m.surface[k]).norm() < 1e-13 * mm.surface[k].norm());
        CHECK((mm.cutter[k] - 1000.0 * m.cutter[k]).norm() < 1e-13 * mm.cutter[k].norm());
        CHECK((um.surface[k] - 1e6 * m.surface[k]).norm() < 1e-13 * um.surface[k].norm());
        CHECK((in.cutter[k] * 25.4 - mm.cutter[k]).norm() < 1e-13 * mm.cutter[k].norm());
    }
    CHECK(std::string(length_unit_name(LengthUnit::inch)) == "inch");
    CHECK(length_unit_from_name("um") == LengthUnit::um);
}

TEST_CASE("the CSV states its conventions, and they are true of its rows") {
    TempDir dir;
    const std::string path = dir.path + "/cam.csv";
    const double rb = 0.030;
    write_cam_csv(path, TranslatingRoller(rb, 0.008, 0.0), paper, 360, 0.008, LengthUnit::mm);
    const std::string text = read_all(path);
    CHECK_THAT(text, Catch::Contains("units: lengths in mm"));
    CHECK_THAT(text, Catch::Contains("the cam turns counter-clockwise viewed from +z"));
    CHECK_THAT(text, Catch::Contains("zero reference: at theta = 0 the cam frame coincides with the ground frame"));
    CHECK_THAT(text, Catch::Contains("polar angle 90 deg"));
    CHECK_THAT(text, Catch::Contains("follower at theta = 0: lift 0 mm, on a dwell"));
    CHECK_THAT(text, Catch::Contains("translating_roller: base_radius = 30 mm, roller_radius = 8 mm, offset = 0 mm"));
    CHECK_THAT(text, Catch::Contains("cutter radius: 8 mm"));
    CHECK_THAT(text, Catch::Contains("points: 360"));

    std::istringstream in(text);
    std::string line;
    std::vector<Vec> surface, cutter;
    std::vector<double> theta;
    bool header_seen = false;
    while (std::getline(in, line)) {
        if (line.rfind("#", 0) == 0) continue;
        if (!header_seen) {
            CHECK(line == "theta_rad,surface_x_mm,surface_y_mm,cutter_x_mm,cutter_y_mm");
            header_seen = true;
            continue;
        }
        double t, sx, sy, cx, cy;
        REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &t, &sx, &sy, &cx, &cy) == 5);
        theta.push_back(t), surface.emplace_back(sx, sy), cutter.emplace_back(cx, cy);
    }
    REQUIRE(surface.size() == 360);
    // Zero mark: on the first dwell a centred roller touches the base circle on +y.
    CHECK(theta[0] == 0.0);
    CHECK((surface[0] - Vec(0.0, 1e3 * rb)).norm() < 1e-12);
    CHECK(theta[90] == Approx(pi / 2).epsilon(1e-15));
    // Rotation: rows run clockwise round the cam (negative signed area), as the header says.
    CHECK(signed_area(surface) < 0.0);
    // Round trip at 17 digits is exact.
    const CamOutline o = cam_outline(TranslatingRoller(rb, 0.008, 0.0), paper, 360, 0.008, LengthUnit::mm);
    for (std::size_t k = 0; k < 360; ++k) CHECK((surface[k] - o.surface[k]).norm() == 0.0);
    // Without a cutter, no cutter columns.
    write_cam_csv(path, TranslatingFlat(rb), paper, 12, std::nullopt, LengthUnit::inch);
    const std::string flat = read_all(path);
    CHECK_THAT(flat, Catch::Contains("\ntheta_rad,surface_x_inch,surface_y_inch\n"));
    CHECK_THAT(flat, Catch::Contains("cutter radius: none"));
    CHECK(dir.entries() == std::vector<std::string>{"cam.csv"});
}

TEST_CASE("the atomic writer refuses non-regular targets and never leaves partial output") {
    TempDir dir;
    const TranslatingRoller f(0.030, 0.008, 0.010);
    SECTION("a directory") {
        ::mkdir((dir.path + "/sub").c_str(), 0755);
        CHECK_THROWS_WITH(write_cam_csv(dir.path + "/sub", f, paper, 36), Catch::Contains("path") &&
                                                                              Catch::Contains("not a regular file") &&
                                                                              Catch::Contains("a directory"));
        CHECK_THROWS_WITH(write_cam_csv(dir.path + "/", f, paper, 36), Catch::Contains("not a regular file"));
        CHECK(dir.entries() == std::vector<std::string>{"sub"});
    }
    SECTION("a FIFO stays a FIFO") {
        const std::string fifo = dir.path + "/pipe";
        REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
        CHECK_THROWS_WITH(write_cam_csv(fifo, f, paper, 36), Catch::Contains("FIFO"));
        struct stat st {};
        REQUIRE(::lstat(fifo.c_str(), &st) == 0);
        CHECK(S_ISFIFO(st.st_mode));
        CHECK(dir.entries() == std::vector<std::string>{"pipe"});
    }
    SECTION("a missing folder") {
        CHECK_THROWS_WITH(write_cam_csv(dir.path + "/none/cam.csv", f, paper, 36),
                          Catch::Contains("cannot create a temporary file"));
        CHECK(dir.entries().empty());
    }
    SECTION("a refused cutter leaves an existing file untouched") {
        const std::string path = dir.path + "/cam.csv";
        write_cam_csv(path, f, paper, 36);
        const std::string before = read_all(path);
        CHECK_THROWS(write_cam_csv(path, TranslatingRoller(0.020, 0.005, 0.0), concave_rise, 36, 0.05));
        CHECK(read_all(path) == before);
        CHECK(dir.entries() == std::vector<std::string>{"cam.csv"});
    }
    SECTION("a write that fails half-way (file size limit) removes its temporary") {
        const std::string path = dir.path + "/cam.csv";
        write_cam_csv(path, f, paper, 36);
        const std::string before = read_all(path);
        rlimit old{};
        REQUIRE(::getrlimit(RLIMIT_FSIZE, &old) == 0);
        const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
        rlimit small = old;
        small.rlim_cur = 4096;
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
        bool threw = false;
        try {
            write_cam_csv(path, f, paper, 3600, 0.008);
        } catch (const std::invalid_argument& e) {
            threw = true;
            CHECK_THAT(std::string(e.what()), Catch::Contains("writing"));
        }
        ::setrlimit(RLIMIT_FSIZE, &old);
        std::signal(SIGXFSZ, old_handler);
        CHECK(threw);
        CHECK(read_all(path) == before);
        CHECK(dir.entries() == std::vector<std::string>{"cam.csv"});
    }
    SECTION("an existing regular file is replaced and keeps its mode") {
        const std::string path = dir.path + "/cam.csv";
        { std::ofstream(path) << "old\n"; }
        ::chmod(path.c_str(), 0600);
        detail::write_file_atomically(path, "new\n");
        CHECK(read_all(path) == "new\n");
        struct stat st {};
        REQUIRE(::stat(path.c_str(), &st) == 0);
        CHECK((st.st_mode & 0777) == 0600);
        CHECK(dir.entries() == std::vector<std::string>{"cam.csv"});
    }
    SECTION("a symbolic link is refused and stays a link to its untouched file") {
        const std::string real = dir.path + "/real.csv", link = dir.path + "/link.csv";
        { std::ofstream(real) << "keep\n"; }
        REQUIRE(::symlink(real.c_str(), link.c_str()) == 0);
        CHECK_THROWS_WITH(detail::write_file_atomically(link, "new\n"), Catch::Contains("symbolic link"));
        struct stat st {};
        REQUIRE(::lstat(link.c_str(), &st) == 0);
        CHECK(S_ISLNK(st.st_mode));
        CHECK(read_all(real) == "keep\n");
        CHECK(dir.entries() == std::vector<std::string>{"link.csv", "real.csv"});
    }
    SECTION("a read-only file is refused, even for root") {
        const std::string path = dir.path + "/cam.csv";
        { std::ofstream(path) << "protected\n"; }
        ::chmod(path.c_str(), 0444);
        CHECK_THROWS_WITH(detail::write_file_atomically(path, "new\n"), Catch::Contains("read-only"));
        CHECK(read_all(path) == "protected\n");
        CHECK(dir.entries() == std::vector<std::string>{"cam.csv"});
    }
    SECTION("an input file is refused under any of its names") {
        const std::string input = dir.path + "/case.toml";
        { std::ofstream(input) << "[camshaft]\n"; }
        ::mkdir((dir.path + "/sub").c_str(), 0755);
        CHECK_THROWS_WITH(detail::write_file_atomically(dir.path + "/sub/../case.toml", "x", "output", {input}),
                          Catch::StartsWith("output: ") && Catch::Contains("is the input file"));
        CHECK(read_all(input) == "[camshaft]\n");
    }
    SECTION("a NUL in the path is refused, not truncated") {
        const std::string path = dir.path + std::string("/a\0b.csv", 8);
        CHECK_THROWS_WITH(detail::write_file_atomically(path, "x"), Catch::Contains("NUL"));
        CHECK(dir.entries().empty());
    }
    SECTION("the temporary's name is unique: a file named like it is left alone") {
        const std::string path = dir.path + "/cam.csv", lookalike = dir.path + "/.cam.csv.tmp";
        { std::ofstream(lookalike) << "someone else's\n"; }
        detail::write_file_atomically(path, "one\n");
        detail::write_file_atomically(path, "two\n");
        CHECK(read_all(path) == "two\n");
        CHECK(read_all(lookalike) == "someone else's\n");
        CHECK(dir.entries() == std::vector<std::string>{".cam.csv.tmp", "cam.csv"});
    }
    SECTION("point counts are bounded") {
        CHECK_THROWS_WITH(write_cam_csv(dir.path + "/cam.csv", f, paper, std::size_t(1) << 40),
                          Catch::Contains("points must be an integer in [3, 10000000]"));
        CHECK(dir.entries().empty());
    }
}
