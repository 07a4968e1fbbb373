#include <catch2/catch.hpp>
#include "config/case_config.hpp"
TEST_CASE("placeholder") { CHECK(true); }
