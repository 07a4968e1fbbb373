// SPDX-License-Identifier: BSD-3-Clause
// Units a config value may carry: a bare number is SI; a string "<number> <unit>" converts from
// one of the units listed for the quantity's kind. The one table of unit factors for config input.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace camfollower::config {

struct UnitFactor {
    const char* unit;
    double factor;  // SI value of one unit
};

struct QuantityKind {
    const char* si;                    // the SI unit the value ends in ("-": dimensionless)
    std::vector<UnitFactor> accepted;  // empty: plain numbers only
};

// The kind named by its SI unit string ("m", "kg", "N/m", "rad", "rpm", ...). Throws for an unknown
// kind (a programming error, not a user error).
const QuantityKind& quantity_kind(std::string_view si);

// SI value of `number` given in `unit` for a quantity of kind `si`; throws std::invalid_argument
// naming the accepted units when `unit` does not fit.
double to_si(double number, std::string_view unit, std::string_view si);

}  // namespace camfollower::config
