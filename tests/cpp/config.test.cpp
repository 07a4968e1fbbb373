// The command line's config parser: units, sections, errors with file, line and key.
#include <catch2/catch.hpp>

#include "config.hpp"

using camfollower::cli::parse_config;

TEST_CASE("config: SI numbers, unit strings, sections") {
    const auto c = parse_config(R"(
# comment
[model]
offset = "12 mm"            # converted
contact_stiffness = 2e8
camshaft_speed_rpm = "15 Hz"
[defects]
eccentricity = "10 um"
backlash_switch_width = "5 deg"
[run]
revolutions = 2
decimation = 4
output = "x.csv"
)");
    CHECK(c.parameters.geometry.offset == Approx(0.012).epsilon(1e-15));
    CHECK(c.parameters.contact_stiffness == 2e8);
    CHECK(c.parameters.camshaft_speed_rpm == Approx(900.0));
    CHECK(c.defects.eccentricity == Approx(10e-6).epsilon(1e-15));
    CHECK(c.defects.backlash_switch_width == Approx(5 * 3.14159265358979 / 180).epsilon(1e-12));
    CHECK(c.revolutions == 2.0);
    CHECK(c.decimation == 4.0);
    CHECK(c.output == "x.csv");
}

TEST_CASE("config: errors name the file, the line and the key") {
    CHECK_THROWS_WITH(parse_config("[model]\noffset = \"10 kg\"\n", "c.toml"),
                      Catch::Contains("c.toml:2: offset: unit 'kg' does not fit this quantity (m)"));
    CHECK_THROWS_WITH(parse_config("[model]\nstiffnes = 1\n", "c.toml"),
                      Catch::Contains("c.toml:2: unknown parameter 'stiffnes'"));
    CHECK_THROWS_WITH(parse_config("[run]\nrevs = 1\n", "c.toml"), Catch::Contains("c.toml:2: revs: unknown key in [run]"));
    CHECK_THROWS_WITH(parse_config("[solver]\n", "c.toml"), Catch::Contains("c.toml:1: unknown section [solver]"));
    CHECK_THROWS_WITH(parse_config("offset = 1\n", "c.toml"), Catch::Contains("keys belong in a [model]"));
    CHECK_THROWS_WITH(parse_config("[model]\nroller_mass = abc\n", "c.toml"), Catch::Contains("'abc' is not a number"));
    CHECK_THROWS_WITH(parse_config("[model]\nroller_mass = -1\n", "c.toml"),
                      Catch::Contains("c.toml: roller_mass must be finite and > 0"));
    // Order does not matter: validation runs once all keys are read.
    CHECK(parse_config("[model]\nbase_radius = 0.005\noffset = 0.0\nroller_radius = 0.002\n").parameters.geometry.offset == 0.0);
    CHECK(parse_config("[run]\noutput = \"a#b.csv\"  # comment\n").output == "a#b.csv");
    CHECK_THROWS_WITH(parse_config("[defects]\neccentricity = -1e-6\n"), Catch::Contains("eccentricity must be finite and >= 0"));
    CHECK_THROWS_WITH(parse_config("[run]\ndecimation = 2.5\n"), Catch::Contains("decimation must be a whole number"));
    CHECK_THROWS_WITH(parse_config("[model]\ncontact_exponent = \"1.5 m\"\n"), Catch::Contains("dimensionless"));
    CHECK_THROWS_WITH(camfollower::cli::load_config("/nonexistent.toml"), Catch::Contains("cannot open"));
}
