// SPDX-License-Identifier: BSD-3-Clause
// The config reader (src/config): units, every part of a mechanism, the preset, and errors that name
// the file, the line and the key. A config's mechanism is checked against the same mechanism built
// directly with the C++ builder (a second route to the same model).
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>

#include "camfollower/camfollower.hpp"
#include "config/case_config.hpp"
#include "camfollower/precompiled.hpp"  // simulate() for the library's mechanisms, compiled once

namespace cf = camfollower;
using cf::config::parse_case;

namespace {

const char* const two_mass = R"(
gravity = [0, -9.81, 0]
[camshaft]
speed = "15 Hz"
[program.p]
segments = [
  { law = "dwell", end = "60 deg" },
  { law = "cycloidal", end = "150 deg", h = "8 mm" },
  { law = "dwell", end = "210 deg", h = "8 mm" },
  { law = "cycloidal", end = "300 deg", h = 0 },
  { law = "dwell", end = "360 deg", h = 0 },
]
[[dof]]
name = "tappet"
mass = "100 g"
direction = [0, 1, 0]
[[dof]]
name = "mid"
mass = 0.02
direction = [0, 1, 0]
[[spring]]
name = "top"
a = "tappet"
b = "mid"
stiffness = "60 N/mm"
preload = 250
[[spring]]
name = "bottom"
a = "mid"
stiffness = 6e4
preload = "0.25 kN"
damping = "3 N s/m"
[[contact]]
name = "cam"
program = "p"
follower = { type = "translating_flat", base_radius = "20 mm" }
follower_dof = "tappet"
stiffness = 2e8
[solver]
revolutions = 1
steps_per_revolution = 8000
[output]
decimation = 4
)";

cf::MechanismBuilder two_mass_by_hand() {
    const auto deg = cf::degrees_to_radians;
    const cf::MotionLaw c = cf::MotionLaw::cycloidal(), d = cf::MotionLaw::dwell();
    const cf::MotionProgram p({{d, 0, deg(60), 0, 0},
                               {c, deg(60), deg(150), 0, 0.008},
                               {d, deg(150), deg(210), 0.008, 0.008},
                               {c, deg(210), deg(300), 0.008, 0},
                               {d, deg(300), cf::two_pi, 0, 0}});
    cf::MechanismBuilder b;
    b.add_dof("tappet", 0.1, {0, 1, 0});
    b.add_dof("mid", 0.02, {0, 1, 0});
    b.add_spring("top", "tappet", "mid", 6e4, 0.0, 250.0);
    b.add_spring("bottom", "mid", "ground", 6e4, 3.0, 250.0);
    b.add_contact({"cam", p, cf::TranslatingFlat(0.02), cf::HertzContact{2e8, 1.0, 0.0}, 0.0, "ground", "ground",
                   "tappet", "ground", cf::CamEccentricity{}, "ground"});
    b.set_gravity({0, -9.81, 0});
    b.set_camshaft_speed_rpm(900.0);
    return b;
}

template <class F>
void simulate_both(const cf::MechanismBuilder& a, const cf::MechanismBuilder& b, F&& check) {
    const cf::Mechanism<Eigen::Dynamic> ma(a), mb(b);
    cf::SolverSettings s;
    s.time_step = ma.period() / 8000;
    cf::RunOptions o;
    o.duration = ma.period();
    o.record.decimation = 40;
    check(cf::simulate(ma, s, o).recording, cf::simulate(mb, s, o).recording);
}

}  // namespace

TEST_CASE("config: a mechanism from its parts is the one the builder makes by hand") {
    const cf::config::CaseConfig c = parse_case(two_mass, "two_mass.toml");
    CHECK(c.preset.empty());
    CHECK(c.mechanism.camshaft_speed_rpm() == Approx(900.0).epsilon(1e-14));
    CHECK(c.solver.steps_per_revolution == 8000);
    CHECK(c.output.decimation == 4);
    const cf::MechanismBuilder hand = two_mass_by_hand();
    const cf::Mechanism<Eigen::Dynamic> a(c.mechanism), b(hand);
    CHECK((a.mass() - b.mass()).norm() == 0.0);
    CHECK((a.stiffness() - b.stiffness()).norm() == 0.0);
    CHECK((a.damping() - b.damping()).norm() == 0.0);
    CHECK((a.initial_displacement() - b.initial_displacement()).norm() <= 1e-15);
    simulate_both(c.mechanism, hand, [](const cf::Recording& x, const cf::Recording& y) {
        REQUIRE(x.rows == y.rows);
        REQUIRE(x.rows > 100);
        double worst = 0.0;
        for (std::size_t i = 0; i < x.rows; ++i)
            worst = std::max(worst, std::abs(x.at("cam.force", i) - y.at("cam.force", i)));
        CHECK(worst <= 1e-9);  // the degree conversion of the angles may differ in the last bit
    });
}

TEST_CASE("config: the paper preset with overrides is presets::paper with those parameters") {
    const cf::config::CaseConfig c = parse_case(R"(
[camshaft]
speed = 900
[preset]
name = "paper"
guide_clearance = "20 um"
eccentricity = { radius = "10 um", phase = "90 deg" }
[preset.parameters]
offset = "5 mm"
contact_stiffness = 2.1e8
)",
                                                "paper.toml");
    CHECK(c.preset == "paper");
    cf::CamFollowerParameters p;
    p.geometry.offset = 0.005;
    p.contact_stiffness = 2.1e8;
    p.camshaft_speed_rpm = 900;
    cf::presets::PaperOptions o;
    o.guide_clearance = 20e-6;
    o.eccentricity.radius = 10e-6;
    o.eccentricity.phase = cf::pi / 2;
    const auto direct = cf::presets::paper(p, cf::MotionProgram::paper_default(), o);
    const cf::Mechanism<cf::presets::paper_dofs> from_config(c.mechanism);
    CHECK((from_config.stiffness() - direct.stiffness()).norm() == 0.0);
    CHECK((from_config.initial_displacement() - direct.initial_displacement()).norm() <= 1e-18);
    CHECK(from_config.clearances().size() == 1);
    CHECK(from_config.contacts().at(0).spec().eccentricity.radius == Approx(10e-6).epsilon(1e-14));
}

TEST_CASE("config: lift tables, polynomial segments and continuity") {
    // A table sampled from a 4-5-6-7 rise between dwells, as one segment, against the closed form.
    std::string theta = "[", h = "[";
    for (int i = 0; i <= 40; ++i) {
        const double x = i / 40.0;
        theta += (i ? ", " : "") + std::to_string(60.0 + 90.0 * x);
        h += (i ? ", " : "") + std::to_string(1e3 * 0.01 * cf::MotionLaw::polynomial_4567().evaluate(x).S);
    }
    const std::string text =
        "[camshaft]\nspeed = 600\n[program.t]\nsegments = [\n { law = \"dwell\", end = \"60 deg\" },\n"
        " { law = \"table\", theta = " +
        theta + "], h = " + h +
        "] },\n"
        " { law = \"polynomial_4567\", end = \"360 deg\", h = 0 },\n]\n"
        "[preset]\nname = \"paper\"\nprogram = \"t\"\n";
    const cf::config::CaseConfig c = parse_case(text, "table.toml");
    const cf::MotionProgram& p = c.program("t");
    const double beta = cf::degrees_to_radians(90.0);
    for (double x : {0.1, 0.37, 0.5, 0.81}) {
        const cf::LawValue v = cf::MotionLaw::polynomial_4567().evaluate(x);
        const cf::FollowerMotion m = p.evaluate(cf::degrees_to_radians(60.0) + x * beta);
        CHECK(m.h == Approx(0.01 * v.S).margin(2e-7));  // the table holds 6 digits in mm
        CHECK(m.d2h == Approx(0.01 * v.A / (beta * beta)).margin(2e-4 * 0.01 * 52.5 / (beta * beta) * 10));
    }
    // Polynomial segment: the 3-4-5 polynomial from its end conditions (the default [0, 0]).
    const cf::config::CaseConfig q = parse_case(R"(
[camshaft]
speed = 600
[program.q]
continuity = 2
segments = [
  { law = "polynomial", end = "180 deg", h = "10 mm" },
  { law = "polynomial", end = "360 deg", h = 0, start_derivatives = [0, 0], end_derivatives = [0, 0] },
]
[preset]
name = "paper"
program = "q"
)");
    const cf::LawValue v = cf::MotionLaw::polynomial_345().evaluate(0.3);
    CHECK(q.program("q").evaluate(0.3 * cf::pi).h == Approx(0.01 * v.S).epsilon(1e-12));
    // continuity = 2 refuses a program whose acceleration jumps (constant acceleration after a dwell).
    CHECK_THROWS_WITH(parse_case(R"(
[camshaft]
speed = 600
[program.q]
continuity = 2
segments = [
  { law = "dwell", end = "30 deg" },
  { law = "constant_acceleration", end = "180 deg", h = "10 mm" },
  { law = "dwell", end = "210 deg" },
  { law = "cycloidal", end = "360 deg", h = 0 },
]
[preset]
name = "paper"
program = "q"
)",
                                 "jump.toml"),
                      Catch::Contains("jump.toml:5: program.q.continuity"));
}

TEST_CASE("config: errors name the file, the line and the key") {
    const std::string head = "[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n";
    const auto fails = [&](const std::string& text, const std::string& expected) {
        CHECK_THROWS_WITH(parse_case(text, "c.toml"), Catch::Contains(expected));
    };
    fails(head + "[preset.parameters]\noffset = \"10 kg\"\n",
          "c.toml:6: preset.parameters.offset: unit 'kg' does not fit this quantity (m)");
    fails(head + "[preset.parameters]\nofset = 0.01\n", "c.toml:6: preset.parameters.ofset: unknown parameter");
    fails(head + "[solver]\nrevs = 1\n", "c.toml:6: solver.revs: unknown key; known here: revolutions");
    fails(head + "[solverr]\n", "c.toml:5: solverr: unknown key");
    fails(head + "[solver]\nrevolutions = 1\nrevolutions = 2\n", "c.toml:7:");  // duplicate keys: a TOML error
    fails(head + "[output]\ndecimation = 2.5\n", "c.toml:6: output.decimation: must be a whole number");
    fails(head + "[output]\ndecimation = 1e300\n", "output.decimation: must be a whole number");
    fails(head + "[output]\ndecimation = 0\n", "output.decimation: must be in [1, ");
    fails(head + "[preset.parameters]\ncontact_damping = \"xnonex\"\n", "contact_damping: must be one of \"none\"");
    fails(head + "[damping]\nrayleigh_alpha = 1\n", "c.toml:5: damping: is not used in this configuration");
    fails(head + "[[dof]]\nname = \"x\"\nmass = 1\n", "describe the mechanism either by its parts or by a preset");
    fails("[preset]\nname = \"paper\"\n", "a [camshaft] table with its speed is required");
    fails(head + "[solver]\nsteps_per_revolution = 8\n", "solver.steps_per_revolution: must be in [16, ");
    fails(head + "[solver]\nrevolutions = nan\n", "solver.revolutions: must be finite");
    fails(
        "[camshaft]\nspeed = 600\n[program.a]\nsegments = [{ law = \"dwell\", end = \"360 deg\" }]\n"
        "[preset]\nname = \"paper\"\nprogram = \"b\"\n",
        "unknown program 'b'; the [program.<name>] tables define: a");
    // A translating follower cannot take an arm angle as its lift.
    fails(
        "[camshaft]\nspeed = 600\n[program.a]\nsegments = [{ law = \"dwell\", end = \"90 deg\" },"
        "{ law = \"cycloidal\", end = \"360 deg\", h = \"0 deg\" }]\n[preset]\nname = \"paper\"\nprogram = \"a\"\n",
        "preset.program: program 'a' lifts by an arm angle");
    // Parts: an unknown DOF, a missing follower table, a bad follower parameter.
    const std::string parts =
        "[camshaft]\nspeed = 600\n[program.a]\nsegments = [{ law = \"dwell\", end = \"90 deg\" },"
        "{ law = \"cycloidal\", end = \"360 deg\", h = \"1 mm\" }]\n";  // closes at 1 mm: refused
    fails(parts, "c.toml:4: program.a.segments:");
    const std::string ok =
        "[camshaft]\nspeed = 600\n[program.a]\nsegments = [{ law = \"cycloidal\", end = \"180 deg\", h = \"1 mm\" },"
        "{ law = \"cycloidal\", end = \"360 deg\", h = 0 }]\n[[dof]]\nname = \"f\"\nmass = 0.1\n";
    fails(ok + "[[spring]]\nname = \"s\"\na = \"g\"\nstiffness = 1e4\n", "c.toml:10: spring[0].a: unknown DOF 'g'");
    fails(ok + "[[contact]]\nname = \"c\"\nprogram = \"a\"\nfollower_dof = \"f\"\nstiffness = 1e8\n",
          "a contact needs a follower table");
    fails(ok + "[[contact]]\nname = \"c\"\nprogram = \"a\"\nfollower_dof = \"f\"\nstiffness = 1e8\n"
               "follower = { type = \"translating_roller\", base_radius = \"-3 mm\", roller_radius = \"5 mm\" }\n",
          "c.toml:13: contact[0].follower.base_radius: must be finite and > 0");
    fails(ok + "[[contact]]\nname = \"c\"\nprogram = \"a\"\nfollower_dof = \"f\"\nstiffness = 1e8\n"
               "follower = { type = \"translating_roler\", base_radius = \"3 mm\" }\n",
          "contact[0].follower.type: must be one of \"translating_roller\"");
}

TEST_CASE("config: a model's error is located at the key it names") {
    // The builders name their parameter; the reader gives that key's line and path (it gave the
    // table's, or for the mechanism's final checks the file alone).
    const std::string ok =
        "[camshaft]\nspeed = 600\n[program.a]\nsegments = [{ law = \"cycloidal\", end = \"180 deg\", h = \"1 mm\" },"
        "{ law = \"cycloidal\", end = \"360 deg\", h = 0 }]\n[[dof]]\nname = \"f\"\nmass = 0.1\n";
    const std::string contact =
        "[[contact]]\nname = \"c\"\nprogram = \"a\"\nfollower_dof = \"f\"\nstiffness = 1e8\n"
        "follower = { type = \"translating_roller\", base_radius = \"30 mm\", roller_radius = \"5 mm\" }\n";
    const auto fails = [&](const std::string& text, const std::string& expected) {
        CHECK_THROWS_WITH(parse_case(text, "c.toml"), Catch::Contains(expected));
    };
    fails(ok + "[[dof]]\nname = \"g\"\n\nmass = -1\n",
          "c.toml:11: dof[1].mass: mass of DOF 'g' must be finite and > 0");
    fails(ok + "[[spring]]\nname = \"s\"\na = \"f\"\n\nstiffness = -1\n",
          "c.toml:12: spring[0].stiffness: stiffness of 's' must be finite and >= 0");
    // Checked when the whole mechanism is built: the element named in the message, then its key.
    fails(ok + "[[spring]]\nname = \"s\"\na = \"f\"\nstiffness = 1e4\n" + contact +
              "[[clearance]]\nname = \"gap\"\ngap_dofs = [\"f\"]\ngap_coefficients = [1]\nclearance = 0.001\nstiffness "
              "= 1e6\n"
              "friction = 0.1\nsliding_dof = \"nope\"\n",
          "c.toml:25: clearance[0].sliding_dof: clearance 'gap' sliding_dof refers to DOF 'nope'");
    fails(ok + "[[spring]]\nname = \"s\"\na = \"f\"\nstiffness = 1e4\n[damping]\nmodal_ratios = [0.1, 0.2]\n",
          "c.toml:13: damping.modal_ratios: give one ratio or one per mode (1), got 2");
    fails("[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n[preset.parameters]\nfollower_mass = 1\noffset = 0.5\n",
          "c.toml:7: preset.parameters.offset: must satisfy |offset| < base_radius + roller_radius");
}

TEST_CASE("config: nesting is bounded, a byte order mark is read") {
    // A BOM (what Windows editors write) is skipped, as Python's reader does (the same parser).
    const std::string text = "[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n";
    CHECK(parse_case("\xEF\xBB\xBF" + text, "bom.toml").preset == "paper");
    std::string dotted = "k";
    for (int i = 0; i < 9999; ++i) dotted += ".k";
    CHECK_THROWS_WITH(parse_case(dotted + " = 1\n" + text, "c.toml"),
                      Catch::Contains("c.toml:1: k.k.k ... (60 more) ... k.k: nested deeper than 64 levels"));
    CHECK_THROWS_WITH(parse_case("x = " + std::string(100, '[') + std::string(100, ']') + "\n" + text, "c.toml"),
                      Catch::Contains("c.toml:1: x[0][0] ... (60 more) ... [0][0]: nested deeper than 64 levels"));
    CHECK_THROWS_WITH(parse_case("x = " + std::string(5000, '[') + std::string(5000, ']') + "\n" + text, "c.toml"),
                      Catch::Contains("c.toml:1:") && Catch::Contains("TOML syntax"));
    // 64 levels are read (and then refused as an unknown key, not for their depth).
    std::string deep = "k";
    for (int i = 0; i < 63; ++i) deep += ".k";
    CHECK_THROWS_WITH(parse_case(deep + " = 1\n" + text, "c.toml"), Catch::Contains("c.toml:1: k: unknown key"));
}

TEST_CASE("config: files: a directory, an empty file, a missing lift table") {
    CHECK_THROWS_WITH(cf::config::load_case("/tmp"), Catch::Contains("'/tmp' is a directory"));
    CHECK_THROWS_WITH(cf::config::load_case("/nonexistent/x.toml"), Catch::Contains("no such file"));
    const std::string empty = "camfollower_test_empty.toml";
    { std::ofstream(empty).flush(); }
    CHECK_THROWS_WITH(cf::config::load_case(empty), Catch::Contains("is empty"));
    std::remove(empty.c_str());
    CHECK_THROWS_WITH(
        parse_case("[camshaft]\nspeed = 600\n[program.m]\nfile = \"no_such_lift.csv\"\n", "c.toml", "/tmp"),
        Catch::Contains("c.toml:4: program.m.file: cannot read the lift table '/tmp/no_such_lift.csv'"));
}

TEST_CASE("config: a program's manufacturing error is the one the API adds") {
    const cf::config::CaseConfig c = parse_case(R"(
[camshaft]
speed = 750
[program.worn]
segments = [
  { law = "dwell", end = "30 deg" },
  { law = "modified_trapezoid", end = "180 deg", h = "10 mm" },
  { law = "dwell", end = "210 deg" },
  { law = "modified_trapezoid", end = "360 deg", h = 0 },
]
[program.worn.error]
waviness = [{ amplitude = "5 um", order = 3, phase = "10 deg" }]
dent = [{ centre = "100 deg", width = "4 deg", depth = "20 um" }]
[preset]
name = "paper"
program = "worn"
)",
                                                "worn.toml");
    const cf::MotionProgram expected = cf::MotionProgram::paper_default().with_profile_error(
        cf::ProfileError::waviness(5e-6, 3, cf::degrees_to_radians(10.0)) +
        cf::ProfileError::dent(cf::degrees_to_radians(100.0), cf::degrees_to_radians(4.0), 20e-6));
    for (double deg : {0.0, 45.0, 99.0, 100.0, 101.5, 250.0}) {
        const double t = cf::degrees_to_radians(deg);
        CHECK(c.program("worn").evaluate(t).h == Approx(expected.evaluate(t).h).margin(1e-15));
        CHECK(c.program("worn").evaluate(t).d2h == Approx(expected.evaluate(t).d2h).margin(1e-9));
    }
    // The dent is in: at its centre the lift differs from the design-plus-waviness lift by its depth.
    const cf::MotionProgram wavy = cf::MotionProgram::paper_default().with_profile_error(
        cf::ProfileError::waviness(5e-6, 3, cf::degrees_to_radians(10.0)));
    const double centre = cf::degrees_to_radians(100.0);
    CHECK(std::abs(c.program("worn").evaluate(centre).h - wavy.evaluate(centre).h) == Approx(20e-6).epsilon(1e-9));
    CHECK_THROWS_WITH(
        parse_case("[camshaft]\nspeed = 750\n[program.w]\nsegments = [{ law = \"dwell\", end = \"360 deg\" }]\n"
                   "[program.w.error]\nwaviness = [{ amplitude = \"5 um\", order = 0 }]\n[preset]\nname = "
                   "\"paper\"\nprogram = \"w\"\n",
                   "w.toml"),
        Catch::Contains("w.toml:6: program.w.error.waviness[0].order: must be in [1, "));
}
