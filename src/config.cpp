#include "config.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace camfollower::cli {

namespace {

struct UnitFactor {
    const char* unit;
    double factor;
};

// Accepted units per kind of quantity (the kind is the SI unit string of the key).
const std::map<std::string, std::vector<UnitFactor>>& units() {
    static const std::map<std::string, std::vector<UnitFactor>> table{
        {"m", {{"m", 1.0}, {"mm", 1e-3}, {"um", 1e-6}, {"µm", 1e-6}}},
        {"kg", {{"kg", 1.0}, {"g", 1e-3}}},
        {"N/m", {{"N/m", 1.0}, {"N/mm", 1e3}, {"N/um", 1e6}}},
        {"N s/m", {{"N s/m", 1.0}, {"N*s/m", 1.0}, {"Ns/m", 1.0}}},
        {"N/m^n", {{"N/m^n", 1.0}}},
        {"m/s", {{"m/s", 1.0}, {"mm/s", 1e-3}}},
        {"m/s^2", {{"m/s^2", 1.0}}},
        {"rpm", {{"rpm", 1.0}, {"rad/s", 60.0 / two_pi}, {"Hz", 60.0}}},
        {"rad", {{"rad", 1.0}, {"deg", pi / 180.0}}},
        {"s", {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}}},
        {"-", {}},
    };
    return table;
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

double parse_number(const std::string& text, const std::string& where) {
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        detail::fail(where, ": '", text, "' is not a number");
    }
    if (used != text.size()) detail::fail(where, ": '", text, "' is not a number");
    return v;
}

// A value: a bare number (SI) or "<number> <unit>" with a unit of the key's kind.
double parse_value(const std::string& raw, const std::string& kind, const std::string& where) {
    if (raw.size() < 2 || raw.front() != '"' || raw.back() != '"') return parse_number(raw, where);
    const std::string inner = trim(raw.substr(1, raw.size() - 2));
    const auto space = inner.find(' ');
    if (space == std::string::npos) return parse_number(inner, where);
    const double number = parse_number(inner.substr(0, space), where);
    const std::string unit = trim(inner.substr(space + 1));
    std::string accepted;
    for (const UnitFactor& u : units().at(kind)) {
        if (unit == u.unit) return number * u.factor;
        accepted += std::string(accepted.empty() ? "" : ", ") + u.unit;
    }
    if (accepted.empty()) detail::fail(where, ": takes a plain number (dimensionless), got unit '", unit, "'");
    detail::fail(where, ": unit '", unit, "' does not fit this quantity (", kind, "); use one of ", accepted);
}

}  // namespace

RunConfig parse_config(const std::string& text, const std::string& origin) {
    RunConfig c;
    std::istringstream in(text);
    std::string line, section;
    const std::map<std::string, std::pair<double Defects::*, const char*>> defect_keys{
        {"eccentricity", {&Defects::eccentricity, "m"}},
        {"eccentricity_phase", {&Defects::eccentricity_phase, "rad"}},
        {"backlash", {&Defects::backlash, "m"}},
        {"backlash_switch_width", {&Defects::backlash_switch_width, "rad"}}};
    const std::map<std::string, std::pair<double RunConfig::*, const char*>> run_keys{
        {"revolutions", {&RunConfig::revolutions, "-"}},
        {"steps_per_revolution", {&RunConfig::steps_per_revolution, "-"}},
        {"time_step", {&RunConfig::time_step, "s"}},
        {"decimation", {&RunConfig::decimation, "-"}}};
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string where_line = detail::concat(origin, ":", number);
        // A '#' starts a comment unless it sits inside a quoted value.
        std::size_t hash = std::string::npos;
        for (std::size_t i = 0, quotes = 0; i < line.size(); ++i) {
            if (line[i] == '"') ++quotes;
            if (line[i] == '#' && quotes % 2 == 0) {
                hash = i;
                break;
            }
        }
        std::string content = trim(hash == std::string::npos ? line : line.substr(0, hash));
        if (content.empty()) continue;
        if (content.front() == '[') {
            if (content.back() != ']') detail::fail(where_line, ": malformed section header '", content, "'");
            section = trim(content.substr(1, content.size() - 2));
            if (section != "model" && section != "defects" && section != "run")
                detail::fail(where_line, ": unknown section [", section, "]; use [model], [defects] or [run]");
            continue;
        }
        const auto eq = content.find('=');
        if (eq == std::string::npos) detail::fail(where_line, ": expected 'key = value', got '", content, "'");
        const std::string key = trim(content.substr(0, eq)), value = trim(content.substr(eq + 1));
        const std::string where = where_line + ": " + key;
        if (section.empty()) detail::fail(where, ": keys belong in a [model], [defects] or [run] section");
        if (section == "model") {
            if (key == "contact_damping") {
                const std::string v = value.size() >= 2 ? value.substr(1, value.size() - 2) : value;
                if (v == "none") c.parameters.contact_damping = ContactDampingModel::none;
                else if (v == "hunt_crossley") c.parameters.contact_damping = ContactDampingModel::hunt_crossley;
                else if (v == "lankarani_nikravesh") c.parameters.contact_damping = ContactDampingModel::lankarani_nikravesh;
                else detail::fail(where, ": must be \"none\", \"hunt_crossley\" or \"lankarani_nikravesh\"");
                continue;
            }
            const char* kind = nullptr;
            for (const auto& f : CamFollowerParameters::fields())
                if (key == f.name) kind = f.unit;
            if (!kind) {
                try {
                    c.parameters.ref(key);
                } catch (const std::invalid_argument& e) {
                    detail::fail(where_line, ": ", e.what());
                }
            }
            c.parameters.ref(key) = parse_value(value, kind, where);  // validated once, at the end
        } else {
            const bool defect = section == "defects";
            if (!defect && key == "output") {
                if (value.size() < 2 || value.front() != '"' || value.back() != '"')
                    detail::fail(where, ": must be a quoted path");
                c.output = value.substr(1, value.size() - 2);
                continue;
            }
            const char* kind = nullptr;
            double* slot = nullptr;
            if (defect) {
                const auto it = defect_keys.find(key);
                if (it != defect_keys.end()) slot = &(c.defects.*(it->second.first)), kind = it->second.second;
            } else {
                const auto it = run_keys.find(key);
                if (it != run_keys.end()) slot = &(c.*(it->second.first)), kind = it->second.second;
            }
            if (!slot)
                detail::fail(where, ": unknown key in [", section, "]; known: ",
                             defect ? "eccentricity, eccentricity_phase, backlash, backlash_switch_width"
                                    : "revolutions, steps_per_revolution, time_step, decimation, output");
            *slot = parse_value(value, kind, where);
        }
    }
    try {
        c.parameters.validate();
        c.defects.validate();
    } catch (const std::invalid_argument& e) {
        detail::fail(origin, ": ", e.what());
    }
    detail::require_positive(c.revolutions, "[run] revolutions");
    detail::require_non_negative(c.time_step, "[run] time_step", "(s)");
    if (!(c.steps_per_revolution >= 100 && std::floor(c.steps_per_revolution) == c.steps_per_revolution))
        detail::fail("[run] steps_per_revolution must be a whole number >= 100, got ", c.steps_per_revolution);
    if (!(c.decimation >= 1 && std::floor(c.decimation) == c.decimation))
        detail::fail("[run] decimation must be a whole number >= 1, got ", c.decimation);
    return c;
}

RunConfig load_config(const std::string& path) {
    std::ifstream in(path);
    if (!in) detail::fail("config: cannot open '", path, "'");
    std::stringstream buffer;
    buffer << in.rdbuf();
    return parse_config(buffer.str(), path);
}

}  // namespace camfollower::cli
