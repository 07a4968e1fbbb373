// SPDX-License-Identifier: BSD-3-Clause
#include "case_config.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <type_traits>

#include "camfollower/camfollower.hpp"
#include "case_from_table.hpp"
#include "dof_motion.hpp"
#include "lengths.hpp"
#include "section.hpp"
#include "units.hpp"
#include "camfollower/contact/line_contact.hpp"

namespace camfollower::config {

namespace {

// Runs f and returns its result; an error f throws without a location gets one in this table: the
// line and path of the key the message names ("stiffness of 'rod' must ..." -> spring[0].stiffness),
// else the table's (one that already names the file passes through). A ConvergenceError (a preset's
// calibration or static equilibrium that cannot be found) stays one, located at the table. With two
// tables, the keys are looked up in `keys` ([preset.parameters]) and a ConvergenceError is `s`'s.
template <class F>
decltype(auto) located(const Section& keys, const Section& s, F&& f) {
    try {
        return f();
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        if (what.rfind(s.origin(), 0) == 0) throw;
        keys.fail_named(what);
    } catch (const ConvergenceError& e) {
        const std::string what = e.what();
        if (what.rfind(s.origin(), 0) == 0) throw;
        throw ConvergenceError(detail::concat(detail::message_text(s.here()), ": ", what));
    }
}
template <class F>
decltype(auto) located(const Section& s, F&& f) {
    return located(s, s, std::forward<F>(f));
}

// A length as written at `key` (value in m): bare when the key holds a number without a unit
// (lengths.hpp checks those against the contact they sit in).
Length written(const Section& s, std::string_view key, double value) {
    return {s.where(key), value, s.has(key) && s.unit(key).empty(), {}};
}
Length written(const Section& s, std::string_view key, std::size_t index, double value) {
    const std::vector<std::string> units = s.units(key);
    return {detail::concat(s.where(key), "[", index, "]"), value, index < units.size() && units[index].empty(), {}};
}

// ---- motion programs -------------------------------------------------------------------------

// Two numeric columns (theta, h) from a text file: comma, semicolon, tab or blank separated; '#'
// comments and one header line of words are skipped.
std::pair<std::vector<double>, std::vector<double>> read_table_file(const Section& s, std::string_view key,
                                                                    const std::string& base_dir) {
    const std::string name = s.text(key);
    const std::string path = !name.empty() && name.front() == '/' ? name : base_dir + "/" + name;
    struct stat st {};
    if (stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        s.fail(key, "cannot read the lift table '" + path + "' (not a regular file)");
    std::ifstream in(path);
    if (!in) s.fail(key, "cannot open the lift table '" + path + "'");
    std::vector<double> theta, h;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        for (char& c : line)
            if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
        std::istringstream row(line);
        row.imbue(std::locale::classic());
        double a = 0.0, b = 0.0;
        std::string rest;
        if (line.find_first_not_of(' ') == std::string::npos) continue;
        if (!(row >> a >> b)) {
            if (theta.empty()) continue;  // a header line
            detail::fail(path, ":", number, ": expected two numbers (theta, h)");
        }
        if (row >> rest) detail::fail(path, ":", number, ": expected two columns (theta, h), found more");
        theta.push_back(a), h.push_back(b);
    }
    if (theta.empty()) s.fail(key, "the lift table '" + path + "' holds no (theta, h) rows");
    return {theta, h};
}

// What a program's lift is: a length (translating followers) or an arm angle (oscillating); bare
// numbers say neither (SI: m or rad).
enum class LiftDimension { unstated, length, angle };

LiftDimension dimension_of(const std::string& unit) {
    if (unit.empty()) return LiftDimension::unstated;
    return unit == "rad" || unit == "deg" ? LiftDimension::angle : LiftDimension::length;
}

const char* dimension_name(LiftDimension d) {
    return d == LiftDimension::angle    ? "an arm angle (rad, deg)"
           : d == LiftDimension::length ? "a length (m, mm, um, inch)"
                                        : "unstated";
}

// Records the dimension of each lift value read and refuses a program that mixes them; keeps the lift
// levels as written (checked against the follower's base radius once a contact uses the program).
struct LiftUnits {
    LiftDimension dimension = LiftDimension::unstated;
    std::vector<Length> levels;
    void note(const Section& s, std::string_view key, const std::string& unit) {
        const LiftDimension d = dimension_of(unit);
        if (d == LiftDimension::unstated) return;
        if (dimension != LiftDimension::unstated && d != dimension)
            s.fail(key, detail::concat("mixes lift units: this program's lift was ", dimension_name(dimension),
                                       ", here it is ", dimension_name(d)));
        dimension = d;
    }
};

struct Table {
    std::vector<double> theta, h;
};

// theta/h arrays or a file, with their units ("deg", "mm" by default: how tables are usually written).
Table read_table(const Section& s, const std::string& base_dir, LiftUnits& lift) {
    const std::string theta_unit = s.text("theta_unit", "deg"), h_unit = s.text("h_unit", "mm");
    lift.note(s, "h_unit", h_unit);
    Table t;
    if (s.has("file")) {
        if (s.has("theta") || s.has("h"))
            s.fail("file", "give the table either as a file or as theta/h arrays, not both");
        auto [theta, h] = read_table_file(s, "file", base_dir);
        try {
            for (double& v : theta) v = to_si(v, theta_unit, "rad");
            for (double& v : h) v = to_si(v, h_unit, "lift");
        } catch (const std::invalid_argument& e) {
            s.fail("theta_unit", e.what());
        }
        t.theta = std::move(theta), t.h = std::move(h);
    } else {
        t.theta = s.quantities("theta", "rad", theta_unit);
        t.h = s.quantities("h", "lift", h_unit);
    }
    if (t.theta.size() != t.h.size())
        s.fail_here(detail::concat("theta and h must have the same length, got ", t.theta.size(), " and ", t.h.size()));
    return t;
}

SplineOptions spline_options(const Section& s) {
    SplineOptions o;
    o.degree = int(s.integer("degree", o.degree, 1, 15));
    o.smoothing = s.quantity("smoothing", "-", o.smoothing);
    return o;
}

MotionLaw named_law(const Section& s, const std::string& law) {
    if (law == "dwell") return MotionLaw::dwell();
    if (law == "simple_harmonic") return MotionLaw::simple_harmonic();
    if (law == "cycloidal") return MotionLaw::cycloidal();
    if (law == "modified_trapezoid") return MotionLaw::modified_trapezoid();
    if (law == "modified_sine") return MotionLaw::modified_sine();
    if (law == "polynomial_345") return MotionLaw::polynomial_345();
    if (law == "polynomial_4567") return MotionLaw::polynomial_4567();
    if (law == "constant_acceleration") return MotionLaw::constant_acceleration();
    // sine_constant_cosine
    const double b = s.quantity("b", "-"), c = s.quantity("c", "-"), d = s.quantity("d", "-");
    try {
        return MotionLaw::sine_constant_cosine(b, c, d);
    } catch (const std::invalid_argument& e) {
        s.fail("b", e.what());
    }
}

Segment read_segment(const Section& s, double start, double level, const std::string& base_dir, LiftUnits& lift) {
    const std::string law =
        s.choice("law", "",
                 {"dwell", "simple_harmonic", "cycloidal", "modified_trapezoid", "modified_sine", "polynomial_345",
                  "polynomial_4567", "constant_acceleration", "sine_constant_cosine", "polynomial", "table"});
    return located(s, [&]() -> Segment {
        if (law == "table") {
            Table t = read_table(s, base_dir, lift);
            std::vector<double> d0, d1;
            if (s.has("start_derivatives")) d0 = s.quantities("start_derivatives", "-");
            if (s.has("end_derivatives")) d1 = s.quantities("end_derivatives", "-");
            Segment seg = Segment::from_table(t.theta, t.h, spline_options(s), d0, d1);
            s.finish({"law", "file", "theta", "h", "theta_unit", "h_unit", "degree", "smoothing", "start_derivatives",
                      "end_derivatives"});
            return seg;
        }
        const double end = s.quantity("end", "rad");
        if (law == "polynomial") {
            lift.note(s, "h", s.unit("h"));
            std::vector<double> d0{level}, d1{s.quantity("h", "lift")};
            lift.levels.push_back(written(s, "h", d1[0]));
            const std::vector<double> zero{0.0, 0.0};
            for (double v : s.has("start_derivatives") ? s.quantities("start_derivatives", "-") : zero) d0.push_back(v);
            for (double v : s.has("end_derivatives") ? s.quantities("end_derivatives", "-") : zero) d1.push_back(v);
            std::vector<std::pair<double, double>> interior;
            if (s.has("interior_theta") || s.has("interior_h")) {
                const std::vector<double> th = s.quantities("interior_theta", "rad"),
                                          hh = s.quantities("interior_h", "lift");
                if (th.size() != hh.size())
                    s.fail("interior_h", "interior_theta and interior_h must have the same length");
                for (std::size_t i = 0; i < th.size(); ++i) {
                    interior.emplace_back(th[i], hh[i]);
                    lift.levels.push_back(written(s, "interior_h", i, hh[i]));
                }
            }
            Segment seg = Segment::polynomial(start, end, d0, d1, interior);
            s.finish({"law", "end", "h", "start_derivatives", "end_derivatives", "interior_theta", "interior_h"});
            return seg;
        }
        const MotionLaw m = named_law(s, law);
        lift.note(s, "h", s.unit("h"));
        const double h = m.is_dwell() ? s.quantity("h", "lift", level) : s.quantity("h", "lift");
        if (s.has("h")) lift.levels.push_back(written(s, "h", h));
        s.finish({"law", "end", "h", "b", "c", "d"});
        return Segment{m, start, end, level, h};
    });
}

// A program's lengths as written: lift levels, and its profile errors' amplitudes and depths.
struct ProgramLengths {
    std::vector<Length> levels;
    std::vector<std::pair<Length, const char*>> errors;
};

// The cam's manufacturing error on a program's lift: waviness orders and dents, summed.
ProfileError read_profile_error(const Section& s, ProgramLengths& lengths) {
    ProfileError e;
    for (const Section& w : s.tables("waviness")) {
        const double amplitude = w.quantity("amplitude", "m"), phase = w.quantity("phase", "rad", 0.0);
        lengths.errors.emplace_back(written(w, "amplitude", amplitude), "the waviness amplitude");
        const long long order = w.integer("order", 0, 1, 100000);
        w.finish({"amplitude", "order", "phase"});
        located(w, [&] { e = e + ProfileError::waviness(amplitude, int(order), phase); });
    }
    for (const Section& d : s.tables("dent")) {
        const double centre = d.quantity("centre", "rad"), width = d.quantity("width", "rad"),
                     depth = d.quantity("depth", "m");
        lengths.errors.emplace_back(written(d, "depth", depth), "the dent depth");
        d.finish({"centre", "width", "depth"});
        located(d, [&] { e = e + ProfileError::dent(centre, width, depth); });
    }
    s.finish({"waviness", "dent"});
    return e;
}

struct NamedProgram {
    MotionProgram program;
    LiftDimension dimension;
    ProgramLengths lengths;
};

NamedProgram read_program(const Section& s, const std::string& base_dir) {
    LiftUnits lift;
    MotionProgram program = [&] {
        if (!s.has("segments")) {
            Table t = read_table(s, base_dir, lift);
            try {
                return MotionProgram::from_table(t.theta, t.h, spline_options(s));
            } catch (const std::invalid_argument& e) {
                s.fail_here(e.what());
            }
        }
        std::vector<Segment> segments;
        lift.note(s, "start_h", s.unit("start_h"));
        double start = 0.0, level = s.quantity("start_h", "lift", 0.0);
        if (s.has("start_h")) lift.levels.push_back(written(s, "start_h", level));
        for (const Section& seg : s.tables("segments")) {
            segments.push_back(read_segment(seg, start, level, base_dir, lift));
            start = segments.back().theta_end, level = segments.back().h_end;
        }
        try {
            return MotionProgram(std::move(segments));
        } catch (const std::invalid_argument& e) {
            s.fail("segments", e.what());
        }
    }();
    if (s.has("continuity")) {
        const long long order = s.integer("continuity", 0, 0, 3);
        try {
            program.require_continuity(int(order));
        } catch (const std::invalid_argument& e) {
            s.fail("continuity", e.what());
        }
    }
    ProgramLengths lengths{std::move(lift.levels), {}};
    if (const std::optional<Section> error = s.table("error")) {
        const ProfileError e = read_profile_error(*error, lengths);
        located(*error, [&] { program = program.with_profile_error(e); });
    }
    s.finish({"segments", "start_h", "file", "theta", "h", "theta_unit", "h_unit", "degree", "smoothing", "continuity",
              "error"});
    return {std::move(program), lift.dimension, std::move(lengths)};
}

// ---- followers and contacts ------------------------------------------------------------------

Eigen::Vector2d point(const Section& s, std::string_view key) {
    const std::vector<double> v = s.quantities(key, "m");
    if (v.size() != 2) s.fail(key, detail::concat("must be [x, y] (m), got ", v.size(), " numbers"));
    return {v[0], v[1]};
}

// Runs `validate` (the model's own checks) with the offset's plausibility (lengths.hpp) checked after
// it: the model refuses an offset beyond the base and roller radii with its message, to which the hint
// is added when the offset is a bare number far too large ("... ; did you mean "5 mm"?").
template <class F>
decltype(auto) with_offset_hint(const ContactLengths& lengths, F&& validate) {
    const auto checked = [&]() -> decltype(auto) {
        try {
            return validate();
        } catch (const std::invalid_argument& e) {
            const std::string problem = offset_problem(lengths);
            if (problem.empty()) throw;
            throw std::invalid_argument(detail::concat(e.what(), "; ", problem));
        }
    };
    if constexpr (std::is_void_v<decltype(validate())>) {
        checked();
        check_follower_lengths(lengths);
    } else {
        auto made = checked();
        check_follower_lengths(lengths);
        return made;
    }
}

// One parameter of a follower as the config writes it (follower/parameters.hpp): a length in m, an
// angle in rad, a point [x, y] in m, a turn by name. A length the plausibility rules know (lengths.hpp)
// is noted in `lengths` as written.
double read_parameter(const Section& s, const FollowerParameter& p, ContactLengths& lengths, double*) {
    if (p.kind == ParameterKind::angle)
        return p.required ? s.quantity(p.name, "rad") : s.quantity(p.name, "rad", p.default_value);
    const double v = p.required ? s.quantity(p.name, "m") : s.quantity(p.name, "m", p.default_value);
    if (std::optional<Length>* slot = lengths.slot(p.name); slot && s.has(p.name)) *slot = written(s, p.name, v);
    return v;
}
Eigen::Vector2d read_parameter(const Section& s, const FollowerParameter& p, ContactLengths& lengths,
                               Eigen::Vector2d*) {
    const Eigen::Vector2d v = point(s, p.name);
    if (std::optional<Length>* slot = lengths.slot(p.name)) {
        Length L = written(s, p.name, v.norm());
        const std::vector<std::string> units = s.units(p.name);
        L.bare = std::all_of(units.begin(), units.end(), [](const std::string& u) { return u.empty(); });
        L.parts = {v.x(), v.y()};
        *slot = L;
    }
    return v;
}
ArmTurn read_parameter(const Section& s, const FollowerParameter& p, ContactLengths&, ArmTurn*) {
    return arm_turn_from(s.choice(p.name, p.required ? "" : arm_turn_name(ArmTurn::counter_clockwise),
                                  {arm_turn_name(ArmTurn::counter_clockwise), arm_turn_name(ArmTurn::clockwise)}));
}

// A follower of type F from its parameters, in their order. Its lengths written as bare numbers are
// checked against each other (lengths.hpp) before it is built, its offset after the model's own check
// (which names an offset beyond the base and roller radii; the hint is added to that message).
template <class F, std::size_t... I>
F read_follower_of(const Section& s, ContactLengths& lengths, std::index_sequence<I...>) {
    const follower_parameter_values<F> values{
        read_parameter(s, F::parameters[I], lengths, static_cast<follower_parameter_type<F, I>*>(nullptr))...};
    check_follower_lengths(lengths, false);
    return with_offset_hint(lengths, [&] { return std::make_from_tuple<F>(values); });
}

// The reader of every type the Follower variant holds: `type` picks one, and only its keys are taken.
template <class... F>
Follower read_follower_among(const Section& s, const std::string& type, ContactLengths& lengths,
                             const std::variant<F...>*) {
    std::optional<Follower> out;
    static_cast<void>(
        ((type == F::type_name &&
          (out = read_follower_of<F>(s, lengths, std::make_index_sequence<F::parameters.size()>{}), true)) ||
         ...));
    // Every type's keys are known here; another type's reads "does not apply here".
    std::vector<std::string_view> keys{"type"};
    const auto add = [&](const auto& parameters) {
        for (const FollowerParameter& p : parameters)
            if (std::find(keys.begin(), keys.end(), p.name) == keys.end()) keys.emplace_back(p.name);
    };
    (add(F::parameters), ...);
    s.finish(keys);
    return *std::move(out);
}

// `owner` names the contact in messages ("contact 'cam'").
Follower read_follower(const Section& s, const std::string& owner) {
    const std::vector<std::string> types = follower_type_names();
    const std::string type = s.choice("type", "", {types.begin(), types.end()});
    return located(s, [&]() -> Follower {
        const bool barrel = type == BarrelRoller::type_name || type == BarrelArmRoller::type_name;
        const char* size = barrel ? "cylinder_radius" : "base_radius";
        ContactLengths lengths{owner, written(s, size, s.quantity(size, "m")), {}, {}, {}, {}, {}};
        if (barrel) lengths.size_name = "the cylinder radius", lengths.barrel = true;
        return read_follower_among(s, type, lengths, static_cast<const Follower*>(nullptr));
    });
}

CamEccentricity read_eccentricity(const Section& s) {
    CamEccentricity e;
    e.radius = s.quantity("radius", "m");
    e.phase = s.quantity("phase", "rad", 0.0);
    const std::string f =
        s.choice("formulation", "exact", {"exact", "paper_force_camshaft", "paper_force_roller", "paper_force_both"});
    e.formulation = f == "exact"                  ? EccentricityFormulation::exact
                    : f == "paper_force_camshaft" ? EccentricityFormulation::paper_force_camshaft
                    : f == "paper_force_roller"   ? EccentricityFormulation::paper_force_roller
                                                  : EccentricityFormulation::paper_force_both;
    e.unbalance_mass = s.quantity("unbalance_mass", "kg", 0.0);
    s.finish({"radius", "phase", "formulation", "unbalance_mass"});
    located(s, [&] { e.validate("eccentricity"); });
    return e;
}

// Contact law: stiffness and exponent, or Palmgren's line-contact law from the roller width.
HertzContact read_law(const Section& s, const char* prefix = "") {
    (void)prefix;
    const double chi = s.quantity("damping_factor", "s/m", 0.0);
    if (s.has("roller_width")) {
        if (s.has("stiffness") || s.has("exponent"))
            s.fail("roller_width", "give either stiffness (and exponent) or roller_width (Palmgren's law), not both");
        try {
            return palmgren_law(s.quantity("roller_width", "m"), chi);
        } catch (const std::invalid_argument& e) {
            s.fail("roller_width", e.what());
        }
    }
    return {s.quantity("stiffness", "N/m^n"), s.quantity("exponent", "-", 1.0), chi};
}

std::string dof_name(const Section& s, std::string_view key, const MechanismBuilder& b, bool ground_ok,
                     std::string_view fallback) {
    const std::string name = s.text(key, fallback);
    if (name == ground_name) {
        if (!ground_ok) s.fail(key, "must name a DOF, not ground");
        return name;
    }
    for (const DofSpec& d : b.structure.dofs())
        if (d.name == name) return name;
    std::vector<std::string> known;
    for (const DofSpec& d : b.structure.dofs()) known.push_back(d.name);
    s.fail(key, "unknown DOF '" + detail::printable(name) + "'; the mechanism defines: " + detail::name_list(known) +
                    (ground_ok ? " (or \"ground\")" : ""));
}

using Dimensions = std::map<std::string, LiftDimension>;
using Lengths = std::map<std::string, ProgramLengths>;

// The lengths of `program` as written, checked against the base radius of the contact `owner` that
// uses it (lengths.hpp): its lift levels when the follower translates, an arm's angles when it
// oscillates (a bare number above a quarter turn), its profile errors' amplitudes and depths.
void check_program_lengths(const ProgramLengths& program, double base_radius, bool translating,
                           const std::string& owner) {
    for (const Length& h : program.levels) {
        if (translating) check_lift(h, base_radius, owner);
        else check_arm_angle(h, owner);
    }
    for (const auto& [L, what] : program.errors) check_small_length(L, what, base_radius, owner);
}

// A translating follower's lift is a length, an oscillating one's an arm angle.
void check_lift_dimension(const Section& s, const Follower& f, LiftDimension d, const std::string& program) {
    const LiftDimension wanted = is_translating(f) ? LiftDimension::length : LiftDimension::angle;
    if (d != LiftDimension::unstated && d != wanted)
        s.fail("program", detail::concat("program '", program, "' gives its lift as ", dimension_name(d), ", but a ",
                                         follower_type_name(f), " follower's lift is ", dimension_name(wanted)));
}

void read_parts(const Section& root, const CaseConfig& c, const Dimensions& dims, const Lengths& lengths,
                MechanismBuilder& b) {
    DofMotions motions;  // what the units of each [[dof]]'s mass say it does: turn or translate
    for (const Section& s : root.tables("dof")) {
        const std::string name = s.text("name");
        const double mass = s.quantity("mass", "kg");
        motions.note(name, s);
        Eigen::Vector3d direction = Eigen::Vector3d::Zero();
        if (s.has("direction")) {
            const std::vector<double> v = s.quantities("direction", "-");
            if (v.size() != 3) s.fail("direction", "must be [x, y, z] (a unit vector, or zeros for a rotation)");
            direction = {v[0], v[1], v[2]};
        }
        s.finish({"name", "mass", "direction"});
        located(s, [&] { b.add_dof(name, mass, direction); });
    }
    // Flexible shafts: every station a bearing, drive, motor or cam names becomes a node.
    std::map<std::string, std::vector<double>> stations;
    for (const char* kind : {"bearing", "drive", "motor", "contact"})
        for (const Section& s : root.tables(kind))
            if (s.has("shaft")) stations[s.text("shaft")].push_back(s.quantity("at", "m", 0.0));
    for (const Section& s : root.tables("shaft")) {
        ShaftSpec spec;
        spec.name = s.text("name");
        const double outer = s.quantity("outer_diameter", "m"), inner = s.quantity("inner_diameter", "m", 0.0);
        const double E = s.quantity("youngs_modulus", "Pa", 210e9), nu = s.quantity("poisson_ratio", "-", 0.3);
        const double rho = s.quantity("density", "kg/m^3", 7850.0);
        located(s, [&] { spec.section = BeamSection::hollow_circle(outer, inner, E, nu, rho); });
        spec.length = s.quantity("length", "m");
        spec.max_element_length = s.quantity("max_element_length", "m", 0.0);
        spec.axial = s.flag("axial", false);
        spec.damping = s.quantity("damping", "s", 0.0);
        spec.stations = stations[spec.name];
        s.finish({"name", "outer_diameter", "inner_diameter", "youngs_modulus", "poisson_ratio", "density", "length",
                  "max_element_length", "axial", "damping"});
        located(s, [&] { b.add_shaft(spec); });
    }
    for (const Section& s : root.tables("bearing")) {
        const std::string name = s.text("name"), shaft = s.text("shaft");
        const double x = s.quantity("at", "m"), k = s.quantity("stiffness", "N/m"),
                     d = s.quantity("damping", "N s/m", 0.0);
        s.finish({"name", "shaft", "at", "stiffness", "damping"});
        located(s, [&] { b.add_bearing(name, shaft, x, k, d); });
    }
    for (const Section& s : root.tables("drive")) {
        const std::string name = s.text("name", "drive"), shaft = s.text("shaft");
        const double x = s.quantity("at", "m", 0.0), k = s.quantity("stiffness", "N/m"),
                     d = s.quantity("damping", "N s/m", 0.0);
        const double inertia = s.quantity("inertia", "kg", 0.0);
        s.finish({"name", "shaft", "at", "stiffness", "damping", "inertia"});
        located(s, [&] {
            b.add_drive(name, shaft, x, k, d);
            if (inertia > 0.0) b.add_mass(b.structure.shaft_dof_at(shaft, x, 3), inertia);
        });
    }
    for (const Section& s : root.tables("motor")) {
        const std::string name = s.text("name", "motor"), shaft = s.text("shaft");
        const double x = s.quantity("at", "m", 0.0), inertia = s.quantity("inertia", "kg");
        const double kp = s.quantity("position_gain", "N/m"), kv = s.quantity("velocity_gain", "N s/m", 0.0);
        const double torque = s.quantity("torque", "N m", 0.0);
        s.finish({"name", "shaft", "at", "inertia", "position_gain", "velocity_gain", "torque"});
        located(s, [&] { b.add_motor(name, shaft, x, inertia, kp, kv, torque); });
    }
    for (const Section& s : root.tables("spring")) {
        const std::string name = s.text("name"), a = dof_name(s, "a", b, false, ""),
                          bb = dof_name(s, "b", b, true, ground_name);
        motions.check(s, "stiffness", Measure::stiffness, {a, bb}, "b");
        motions.check(s, "damping", Measure::damping, {a, bb}, "b");
        motions.check(s, "preload", Measure::force, {a, bb}, "b");
        const double k = s.quantity("stiffness", "N/m"), d = s.quantity("damping", "N s/m", 0.0),
                     p = force_or_moment(s, "preload", 0.0);
        s.finish({"name", "a", "b", "stiffness", "damping", "preload"});
        located(s, [&] { b.add_spring(name, a, bb, k, d, p); });
    }
    for (const Section& s : root.tables("damper")) {
        const std::string name = s.text("name"), a = dof_name(s, "a", b, false, ""),
                          bb = dof_name(s, "b", b, true, ground_name);
        motions.check(s, "damping", Measure::damping, {a, bb}, "b");
        const double d = s.quantity("damping", "N s/m");
        s.finish({"name", "a", "b", "damping"});
        located(s, [&] { b.add_damper(name, a, bb, d); });
    }
    for (const Section& s : root.tables("spring_chain")) {
        const std::string name = s.text("name"), a = dof_name(s, "a", b, false, ""),
                          bb = dof_name(s, "b", b, true, ground_name);
        const double k = s.quantity("stiffness", "N/m"), m = s.quantity("mass", "kg");
        const int elements = int(s.integer("elements", 6, 1, 1000));
        const double d = s.quantity("damping", "N s/m", 0.0), p = s.quantity("preload", "N", 0.0);
        Eigen::Vector3d direction = Eigen::Vector3d::Zero();
        if (s.has("direction")) {
            const std::vector<double> v = s.quantities("direction", "-");
            if (v.size() != 3) s.fail("direction", "must be [x, y, z] (a unit vector)");
            direction = {v[0], v[1], v[2]};
        }
        s.finish({"name", "a", "b", "stiffness", "mass", "elements", "damping", "preload", "direction"});
        located(s, [&] { b.add_spring_chain(name, a, bb, k, m, elements, d, p, direction); });
    }
    for (const Section& s : root.tables("load")) {
        const std::string dof = dof_name(s, "dof", b, false, "");
        motions.check(s, "force", Measure::force, {dof}, "dof");
        const double f = force_or_moment(s, "force");
        s.finish({"dof", "force"});
        located(s, [&] { b.add_load(dof, f); });
    }
    for (const Section& s : root.tables("contact")) {
        ContactPairSpec p{s.text("name"),
                          MotionProgram::paper_default(),
                          TranslatingRoller(0.03, 0.008, 0.0),
                          HertzContact{},
                          0.0,
                          ground_name,
                          ground_name,
                          "",
                          ground_name,
                          CamEccentricity{},
                          ground_name};
        const std::string program = s.text("program");
        located(s, [&] { p.program = c.program(program); });
        const std::optional<Section> follower = s.table("follower");
        if (!follower)
            s.fail_here("a contact needs a follower table: follower = { type = \"translating_roller\", ... }");
        const std::string owner = "contact '" + detail::printable(p.name) + "'";
        p.follower = read_follower(*follower, owner);
        check_lift_dimension(s, p.follower, dims.at(program), program);
        const double base_radius = cam_radius(p.follower);
        check_program_lengths(lengths.at(program), base_radius, is_translating(p.follower), owner);
        p.law = read_law(s);
        p.phase = s.quantity("phase", "rad", 0.0);
        p.follower_dof = dof_name(s, "follower_dof", b, false, "");
        p.cam_x = dof_name(s, "cam_x", b, true, ground_name);
        p.cam_y = dof_name(s, "cam_y", b, true, ground_name);
        p.lateral = dof_name(s, "lateral", b, true, ground_name);
        p.cam_twist = dof_name(s, "cam_twist", b, true, ground_name);
        const bool translating = is_translating(p.follower);
        motions.require(
            s, "follower_dof", p.follower_dof, translating ? DofMotion::translation : DofMotion::rotation,
            translating ? "a translating follower's lift (m)" : "an oscillating follower's arm angle (rad)");
        motions.require(s, "cam_x", p.cam_x, DofMotion::translation, "the cam centre's x displacement (m)");
        motions.require(s, "cam_y", p.cam_y, DofMotion::translation, "the cam centre's y displacement (m)");
        motions.require(s, "lateral", p.lateral, DofMotion::translation, "the follower's lateral displacement (m)");
        motions.require(s, "cam_twist", p.cam_twist, DofMotion::rotation, "the cam's twist angle (rad)");
        if (const std::optional<Section> e = s.table("eccentricity")) {
            p.eccentricity = read_eccentricity(*e);
            check_small_length(written(*e, "radius", p.eccentricity.radius), "the eccentricity radius", base_radius,
                               owner);
        }
        if (const std::optional<Section> g = s.table("groove")) {
            // A face groove's outer flank (contact/groove.hpp): its clearance, and its own contact law
            // when any law key is given (the contact's otherwise).
            Groove groove;
            groove.clearance = g->quantity("clearance", "m");
            if (g->has("stiffness") || g->has("exponent") || g->has("damping_factor") || g->has("roller_width"))
                groove.law = read_law(*g);
            g->finish({"clearance", "stiffness", "exponent", "damping_factor", "roller_width"});
            p.groove = groove;
        }
        const bool mounted = s.has("shaft");
        std::string shaft;
        double x = 0.0, width = 0.0, mass = 0.0, inertia = 0.0;
        if (mounted) {
            // Mounted on a flexible shaft: the node's DOFs are the cam's centre and twist.
            for (const char* key : {"cam_x", "cam_y", "cam_twist"})
                if (s.has(key)) s.fail(key, "is the shaft's node DOF for a cam mounted on a shaft; leave it out");
            shaft = s.text("shaft");
            x = s.quantity("at", "m"), width = s.quantity("width", "m", 0.0);
            mass = s.quantity("cam_mass", "kg", 0.0), inertia = s.quantity("cam_inertia", "kg", 0.0);
        } else {
            for (const char* key : {"at", "width", "cam_mass", "cam_inertia"})
                if (s.has(key)) s.fail(key, "belongs to a cam mounted on a shaft (give shaft = \"<name>\")");
        }
        // Conjugate cams (contact/conjugate.hpp): this contact's cam lifts, a second cam returns.
        std::optional<ConjugateCams> conjugate;
        if (const std::optional<Section> j = s.table("conjugate")) {
            for (const char* key : {"groove", "eccentricity", "shaft"})
                if (s.has(key)) s.fail(key, "does not combine with conjugate cams (not modelled)");
            const std::optional<Section> back = j->table("follower");
            if (!back) j->fail_here("conjugate cams need the return cam's follower: follower = { type = ... }");
            conjugate =
                ConjugateCams{p.name,       p.program,  p.follower,   read_follower(*back, owner + "'s return cam"),
                              std::nullopt, p.law,      std::nullopt, p.phase,
                              0.0,          p.cam_x,    p.cam_y,      p.follower_dof,
                              p.lateral,    p.cam_twist};
            if (j->has("program")) {
                const std::string name = j->text("program");
                located(*j, [&] { conjugate->return_program = c.program(name); });
            }
            conjugate->backlash = j->quantity("backlash", translating ? "m" : "rad", 0.0);
            if (j->has("stiffness") || j->has("exponent") || j->has("damping_factor") || j->has("roller_width"))
                conjugate->return_law = read_law(*j);
            j->finish({"follower", "program", "backlash", "stiffness", "exponent", "damping_factor", "roller_width"});
        }
        s.finish({"name",   "program",      "follower", "stiffness", "exponent", "damping_factor", "roller_width",
                  "phase",  "follower_dof", "cam_x",    "cam_y",     "lateral",  "cam_twist",      "eccentricity",
                  "groove", "shaft",        "at",       "width",     "cam_mass", "cam_inertia",    "conjugate"});
        if (conjugate) located(s, [&] { b.add_conjugate_cams(*conjugate); });
        else if (mounted) located(s, [&] { b.mount_cam(p, shaft, x, width, mass, inertia); });
        else located(s, [&] { b.add_contact(p); });
    }
    for (const Section& s : root.tables("clearance")) {
        ClearanceSpec cl;
        cl.name = s.text("name");
        const std::vector<std::string> dofs = s.texts("gap_dofs");
        const std::vector<double> coefficients = s.quantities("gap_coefficients", "-");
        if (dofs.size() != coefficients.size()) s.fail("gap_coefficients", "needs one coefficient per gap_dofs entry");
        for (std::size_t i = 0; i < dofs.size(); ++i) cl.gap.emplace_back(dofs[i], coefficients[i]);
        cl.clearance = s.quantity("clearance", "m");
        cl.wall = read_law(s);
        cl.friction = s.quantity("friction", "-", 0.0);
        cl.sliding_dof = s.text("sliding_dof", "");
        cl.slip_velocity = s.quantity("slip_velocity", "m/s", cl.slip_velocity);
        s.finish({"name", "gap_dofs", "gap_coefficients", "clearance", "stiffness", "exponent", "damping_factor",
                  "roller_width", "friction", "sliding_dof", "slip_velocity"});
        located(s, [&] { b.add_clearance(cl); });
    }
    for (const Section& s : root.tables("guide")) {
        GuideSpec g;
        g.name = s.text("name");
        g.lateral_dof = dof_name(s, "lateral_dof", b, false, "");
        if (s.has("tilt_dof")) g.tilt_dof = dof_name(s, "tilt_dof", b, false, "");
        if (s.has("sliding_dof")) g.sliding_dof = dof_name(s, "sliding_dof", b, false, "");
        g.length = s.quantity("length", "m");
        g.bushings = s.quantities("bushings", "m");
        g.tilt_reference = s.quantity("tilt_reference", "m", 0.0);
        g.clearance = s.quantity("clearance", "m");
        g.wall = read_law(s);
        g.friction = s.quantity("friction", "-", 0.0);
        g.slip_velocity = s.quantity("slip_velocity", "m/s", g.slip_velocity);
        s.finish({"name", "lateral_dof", "tilt_dof", "sliding_dof", "length", "bushings", "tilt_reference", "clearance",
                  "stiffness", "exponent", "damping_factor", "roller_width", "friction", "slip_velocity"});
        located(s, [&] { b.add_guide(g); });
    }
    // [[linkage]]: a swing arm driving a slider or a rocker through a coupler (linkage/coupler_linkage.hpp).
    for (const Section& s : root.tables("linkage")) {
        CouplerLinkage l;
        l.name = s.text("name");
        l.arm_dof = dof_name(s, "arm_dof", b, false, "");
        l.arm_pivot = s.has("arm_pivot") ? point(s, "arm_pivot") : Eigen::Vector2d::Zero();
        l.arm_length = s.quantity("arm_length", "m");
        l.arm_angle = s.quantity("arm_angle", "rad");
        l.arm_turn =
            arm_turn_from(s.choice("arm_turn", arm_turn_name(ArmTurn::counter_clockwise),
                                   {arm_turn_name(ArmTurn::counter_clockwise), arm_turn_name(ArmTurn::clockwise)}));
        l.joint_stiffness = s.quantity("joint_stiffness", "N/m");
        l.joint_damping = s.quantity("joint_damping", "N s/m", 0.0);
        const std::optional<Section> coupler = s.table("coupler");
        if (!coupler) s.fail_here("needs coupler = { length = ..., mass = ..., inertia = ... }");
        l.coupler_length = coupler->quantity("length", "m");
        l.coupler_mass = coupler->quantity("mass", "kg");
        l.coupler_inertia = coupler->quantity("inertia", "kg");
        coupler->finish({"length", "mass", "inertia"});
        const std::optional<Section> out = s.table("output");
        if (!out) s.fail_here("needs output = { type = \"slider\" | \"rocker\", dof = ..., ... }");
        const bool slider = out->choice("type", "slider", {"slider", "rocker"}) == "slider";
        l.output = slider ? CouplerLinkage::Output::slider : CouplerLinkage::Output::rocker;
        l.output_dof = dof_name(*out, "dof", b, false, "");
        l.branch = int(out->integer("branch", 1, -1, 1));
        if (l.branch == 0) out->fail("branch", "must be +1 or -1 (which of the two assemblies), got 0");
        if (slider) {
            l.output_origin = point(*out, "origin");
            l.output_direction = out->quantity("direction", "rad", 0.0);
            out->finish({"type", "dof", "branch", "origin", "direction"});
        } else {
            l.output_origin = point(*out, "pivot");
            l.output_length = out->quantity("length", "m");
            l.output_turn = arm_turn_from(
                out->choice("turn", arm_turn_name(ArmTurn::counter_clockwise),
                            {arm_turn_name(ArmTurn::counter_clockwise), arm_turn_name(ArmTurn::clockwise)}));
            out->finish({"type", "dof", "branch", "pivot", "length", "turn"});
        }
        s.finish({"name", "arm_dof", "arm_pivot", "arm_length", "arm_angle", "arm_turn", "coupler", "output",
                  "joint_stiffness", "joint_damping"});
        located(s, [&] { b.add_linkage(l); });
    }
    if (const std::optional<Section> s = root.table("damping")) {
        const double alpha = s->quantity("rayleigh_alpha", "-", 0.0), beta = s->quantity("rayleigh_beta", "-", 0.0);
        if (alpha != 0.0 || beta != 0.0) located(*s, [&] { b.set_rayleigh_damping(alpha, beta); });
        if (s->has("modal_ratios")) {
            const std::vector<double> r = s->quantities("modal_ratios", "-");
            located(*s, [&] { b.set_modal_damping(r); });
            // Every DOF is defined by now: the count is checked here, where the key's line is known,
            // rather than when the mechanism is built.
            const std::size_t n = std::size_t(b.structure.size());
            if (r.size() != 1 && r.size() != n)
                s->fail("modal_ratios", detail::concat("give one ratio or one per mode (", n, "), got ", r.size()));
        }
        s->finish({"rayleigh_alpha", "rayleigh_beta", "modal_ratios"});
    }
    if (root.has("gravity")) {
        const std::vector<double> g = root.quantities("gravity", "m/s^2");
        if (g.size() != 3) root.fail("gravity", "must be [x, y, z] (m/s^2)");
        b.set_gravity({g[0], g[1], g[2]});
    }
}

// ---- the paper preset ------------------------------------------------------------------------

// [camshaft] run_up, run_down and modulation: a speed program around `speed` (its nominal speed).
//   run_up = { from = "0 rpm", start = "0 s", duration = "0.5 s", shape = "smooth" }
//   run_down = { start = "3 s", duration = "0.5 s", to = "0 rpm", shape = "smooth" }
//   modulation = { amplitude = 0.1, harmonic = 2, phase = "0 deg" }
std::optional<SpeedProgram> read_speed_program(const Section& cam, double rpm) {
    const std::optional<Section> up = cam.table("run_up"), down = cam.table("run_down"), mod = cam.table("modulation");
    if (!up && !down && !mod) return std::nullopt;
    const double speed = rpm * two_pi / 60.0;
    double initial = speed, end_of_run_up = 0.0;
    std::vector<SpeedRamp> ramps;
    const auto shape = [](const Section& s) {
        return ramp_shape_from(s.choice("shape", "smooth", {"smooth", "linear"}));
    };
    const auto duration = [](const Section& s) {
        const double d = s.quantity("duration", "s");
        if (!(d > 0.0 && d <= 1e6)) s.fail("duration", detail::concat("must be in (0, 1e6] s, got ", d, " s"));
        return d;
    };
    if (up) {
        const double from = up->quantity("from", "rpm", 0.0);
        if (!(from >= 0.0 && from < rpm))
            up->fail("from", detail::concat("must be in [0, speed) = [0, ", rpm, ") rpm, got ", from, " rpm"));
        const double start = up->quantity("start", "s", 0.0);
        if (!(start >= 0.0 && start <= 1e6))
            up->fail("start", detail::concat("must be in [0, 1e6] s, got ", start, " s"));
        initial = from * two_pi / 60.0;
        ramps.push_back({start, duration(*up), speed, shape(*up)});
        end_of_run_up = start + ramps.back().duration;
        up->finish({"from", "start", "duration", "shape"});
    }
    if (down) {
        const double start = down->quantity("start", "s");
        if (!(start >= end_of_run_up && start <= 1e6))
            down->fail("start", detail::concat("must be in [", end_of_run_up, ", 1e6] s (after the run-up ends), got ",
                                               start, " s"));
        const double to = down->quantity("to", "rpm", 0.0);
        if (!(to >= 0.0 && to < rpm))
            down->fail("to", detail::concat("must be in [0, speed) = [0, ", rpm, ") rpm, got ", to, " rpm"));
        ramps.push_back({start, duration(*down), to * two_pi / 60.0, shape(*down)});
        down->finish({"start", "duration", "to", "shape"});
    }
    std::optional<SpeedModulation> modulation;
    if (mod) {
        SpeedModulation m;
        m.amplitude = mod->quantity("amplitude", "-");
        if (!(std::abs(m.amplitude) < 1.0))
            mod->fail(
                "amplitude",
                detail::concat("must be in (-1, 1) (a fraction of the speed; at +-1 the camshaft would stop), got ",
                               m.amplitude));
        m.harmonic = int(mod->integer("harmonic", 1, 1, 1000));
        m.phase = mod->quantity("phase", "rad", 0.0);
        modulation = m;
        mod->finish({"amplitude", "harmonic", "phase"});
    }
    return SpeedProgram(initial, std::move(ramps), modulation);
}

// The valve-train preset: parameters by name (SI units as in presets::ValveTrainParameters); the
// camshaft speed is [camshaft] speed (the engine turns twice as fast).
MechanismBuilder read_valve_train(const Section& s, double rpm) {
    presets::ValveTrainParameters p;
    const std::optional<Section> ps = s.table("parameters");
    if (ps) {
        for (const std::string& key : ps->keys()) {
            if (key == "cylinders") p.cylinders = int(ps->integer(key, p.cylinders, 1, 64));
            else if (key == "valves_per_cylinder")
                p.valves_per_cylinder = int(ps->integer(key, p.valves_per_cylinder, 1, 2));
            else if (key == "spring_elements") p.spring_elements = int(ps->integer(key, p.spring_elements, 1, 1000));
            else if (key == "firing_order") {
                p.firing_order.clear();
                for (double v : ps->quantities(key, "-")) {
                    if (v != std::floor(v) || v < 1 || v > 64) ps->fail(key, "must list cylinder numbers 1, 2, ...");
                    p.firing_order.push_back(int(v));
                }
            } else {
                const char* unit = nullptr;
                try {
                    unit = presets::ValveTrainParameters::unit_of(key);
                } catch (const std::invalid_argument& e) {
                    ps->fail(key, e.what());
                }
                p.ref(key) = ps->quantity(key, unit);
            }
        }
    }
    if (ps) {
        const auto as_written = [&](const char* key, double v) {
            return ps->has(key) ? written(*ps, key, v) : Length{"", v, false, {}};
        };
        const std::string owner = "the valve-train preset's cams";
        ContactLengths lengths{owner, as_written("base_radius", p.base_radius), {}, {}, {}, {}, {}};
        lengths.roller_radius = as_written("roller_radius", p.roller_radius);
        check_follower_lengths(lengths);
        check_lift(as_written("lift", p.lift), p.base_radius, owner);
    }
    p.engine_speed_rpm = 2.0 * rpm;
    s.finish({"name", "parameters"});
    MechanismBuilder b;
    // The preset's messages name its parameters: located at the one in [preset.parameters].
    located(ps ? *ps : s, s, [&] { b = presets::valve_train(p); });
    return b;
}

MechanismBuilder read_preset(const Section& s, const CaseConfig& c, const Dimensions& dims, const Lengths& lengths,
                             double rpm) {
    const std::string name = s.choice("name", "", {"paper", "paper_damped", "valve_train"});
    if (name == "valve_train") return read_valve_train(s, rpm);
    CamFollowerParameters p;
    const std::optional<Section> ps = s.table("parameters");
    if (ps) {
        for (const std::string& key : ps->keys()) {
            if (key == "contact_damping") continue;  // a choice, read below
            if (key == "camshaft_speed_rpm") ps->fail(key, "set the speed once, in [camshaft] speed");
            const char* kind = nullptr;
            for (const auto& f : CamFollowerParameters::fields())
                if (key == f.name) kind = f.unit;
            if (!kind) {
                std::string known;
                for (const auto& f : CamFollowerParameters::fields())
                    if (std::string(f.name) != "camshaft_speed_rpm")
                        known += (known.empty() ? "" : ", ") + std::string(f.name);
                ps->fail(key, "unknown parameter; known: " + known + ", contact_damping");
            }
            p.ref(key) = ps->quantity(key, kind);
        }
        if (ps->has("contact_damping")) {
            const std::string d = ps->choice("contact_damping", "", {"none", "hunt_crossley", "lankarani_nikravesh"});
            p.contact_damping = d == "none"            ? ContactDampingModel::none
                                : d == "hunt_crossley" ? ContactDampingModel::hunt_crossley
                                                       : ContactDampingModel::lankarani_nikravesh;
        }
    }
    p.camshaft_speed_rpm = rpm;
    const std::string owner = "the paper preset's cam";
    const auto as_written = [&](const char* key) {
        return ps && ps->has(key) ? written(*ps, key, p.get(key)) : Length{"", p.get(key), false, {}};
    };
    ContactLengths geometry{owner, as_written("base_radius"), {}, {}, {}, {}, {}};
    geometry.roller_radius = as_written("roller_radius");
    geometry.offset = as_written("offset");
    check_follower_lengths(geometry, false);
    // "offset must satisfy ...": at preset.parameters.offset
    located(ps ? *ps : s, s, [&] { with_offset_hint(geometry, [&] { p.validate(); }); });
    presets::PaperOptions o;
    if (const std::optional<Section> e = s.table("eccentricity")) {
        o.eccentricity = read_eccentricity(*e);
        check_small_length(written(*e, "radius", o.eccentricity.radius), "the eccentricity radius",
                           p.geometry.base_radius, owner);
    }
    o.guide_clearance = s.quantity("guide_clearance", "m", 0.0);
    o.guide_wall_damping_factor = s.quantity("guide_wall_damping_factor", "s/m", 0.0);
    o.guide_friction = s.quantity("guide_friction", "-", 0.0);
    o.element_damping_ratio =
        s.quantity("element_damping_ratio", "-", name == "paper_damped" ? presets::realistic_damping_ratio : 0.0);
    o.paper_backlash = s.quantity("paper_backlash", "m", 0.0);
    o.paper_backlash_switch_width = s.quantity("paper_backlash_switch_width", "rad", 0.0);
    if (name == "paper_damped" && o.element_damping_ratio == 0.0)
        s.fail("element_damping_ratio",
               "paper_damped needs a ratio in (0, 1); use name = \"paper\" for the paper's dampers");
    MotionProgram program = MotionProgram::paper_default();
    if (s.has("program")) {
        const std::string pname = s.text("program");
        located(s, [&] { program = c.program(pname); });
        if (dims.at(pname) == LiftDimension::angle)
            s.fail("program", "program '" + pname +
                                  "' lifts by an arm angle; the paper preset's follower translates (give a length)");
        check_program_lengths(lengths.at(pname), p.geometry.base_radius, true, owner);
    }
    s.finish({"name", "parameters", "eccentricity", "guide_clearance", "guide_wall_damping_factor", "guide_friction",
              "element_damping_ratio", "paper_backlash", "paper_backlash_switch_width", "program"});
    MechanismBuilder b;
    located(s, [&] { b = presets::paper(p, program, o).description(); });
    return b;
}

// ---- solver and output -----------------------------------------------------------------------

SolverConfig read_solver(const Section& s) {
    SolverConfig v;
    if (s.has("duration") && s.has("revolutions")) s.fail("duration", "give revolutions or duration, not both");
    v.revolutions = s.quantity("revolutions", "-", v.revolutions);
    if (!(v.revolutions > 0.0 && v.revolutions <= 1e6))
        s.fail("revolutions", detail::concat("must be in (0, 1e6], got ", v.revolutions));
    v.duration = s.quantity("duration", "s", 0.0);
    if (s.has("duration") && !(v.duration > 0.0)) s.fail("duration", "must be > 0 s");
    if (s.has("time_step") && s.has("steps_per_revolution"))
        s.fail("time_step", "give time_step or steps_per_revolution, not both");
    v.time_step = s.quantity("time_step", "s", 0.0);
    if (s.has("time_step") && !(v.time_step > 0.0)) s.fail("time_step", "must be > 0 s");
    v.steps_per_revolution = s.integer("steps_per_revolution", v.steps_per_revolution, 16, 1LL << 26);
    // The methods' names (solver/settings.hpp), and "average_acceleration": newmark at gamma = 1/2, beta = 1/4.
    std::vector<std::string_view> schemes{"average_acceleration"};
    for (const MethodTraits& t : method_table) schemes.push_back(t.name);
    const std::string scheme = s.choice("scheme", "average_acceleration", schemes);
    SolverSettings& n = v.settings;
    if (scheme != "average_acceleration") n.method = method_from_name(scheme);
    if (n.method == Method::hht) n.hht_alpha = s.quantity("hht_alpha", "-", default_hht_alpha);
    // "newmark" by name takes gamma and beta (average_acceleration is newmark at their defaults).
    const bool named_newmark = scheme == method_name(Method::newmark);
    if (named_newmark) {
        n.gamma = s.quantity("gamma", "-");
        n.beta = s.quantity("beta", "-");
    }
    // With a tolerance every method adapts its steps ("auto" chooses among dop853 and radau); the
    // Runge-Kutta methods have one by default.
    if (s.has("tolerance")) n.tolerance = s.quantity("tolerance", "-");
    give_default_tolerance(n);
    if (n.tolerance) {
        n.max_step = s.quantity("max_step", "s", n.max_step);
    } else if (s.has("max_step")) {
        s.fail("max_step",
               "applies with a tolerance only (scheme = \"" + scheme + "\" without one runs fixed steps of time_step)");
    }
    n.residual_tolerance = s.quantity("residual_tolerance", "-", n.residual_tolerance);
    n.increment_tolerance = s.quantity("increment_tolerance", "-", n.increment_tolerance);
    n.max_iterations = int(s.integer("max_iterations", n.max_iterations, 1, 1000));
    n.max_halvings = int(s.integer("max_halvings", n.max_halvings, 0, 30));
    set_linear_solver(n, s.choice("linear_solver", "auto", {"auto", "low_rank", "dense_lu", "sparse", "klu"}));
    v.settle = s.flag("settle", false);
    v.settle_tolerance = s.quantity("settle_tolerance", "-", v.settle_tolerance);
    if (s.has("settle_dofs")) v.settle_dofs = s.texts("settle_dofs");
    v.settle_min_revolutions = int(s.integer("settle_min_revolutions", v.settle_min_revolutions, 2, 100000));
    v.settle_max_revolutions = int(s.integer("settle_max_revolutions", v.settle_max_revolutions, 2, 100000));
    if (!v.settle)
        for (const char* k : {"settle_tolerance", "settle_dofs", "settle_min_revolutions", "settle_max_revolutions"})
            if (s.has(k)) s.fail(k, "applies only with settle = true");
    if (n.method != Method::hht && s.has("hht_alpha"))
        s.fail("hht_alpha", detail::concat("applies only with scheme = \"", method_name(Method::hht), "\""));
    for (const char* k : {"gamma", "beta"})
        if (!named_newmark && s.has(k))
            s.fail(k, detail::concat("applies only with scheme = \"", method_name(Method::newmark), "\" (\"", scheme,
                                     "\" sets its own)"));
    s.finish({"revolutions",
              "duration",
              "time_step",
              "steps_per_revolution",
              "scheme",
              "hht_alpha",
              "gamma",
              "beta",
              "residual_tolerance",
              "increment_tolerance",
              "max_iterations",
              "max_halvings",
              "linear_solver",
              "settle",
              "tolerance",
              "max_step",
              "settle_tolerance",
              "settle_dofs",
              "settle_min_revolutions",
              "settle_max_revolutions"});
    SolverSettings check = n;
    check.time_step = 1.0;
    located(s, [&] { check.validate(); });
    return v;
}

OutputConfig read_output(const Section& s) {
    OutputConfig o;
    o.file = s.text("file", "");
    o.decimation = s.integer("decimation", 1, 1, 1LL << 40);
    o.record_last_revolutions = s.quantity("record_last_revolutions", "-", 0.0);
    if (s.has("record_last_revolutions") && !(o.record_last_revolutions > 0.0))
        s.fail("record_last_revolutions", "must be > 0");
    s.finish({"file", "decimation", "record_last_revolutions"});
    return o;
}

// A recording with no row, or one (nothing to draw), is a mistake in [output]: refused by its key.
void check_recording(const Section& s, const SolverConfig& solver, const OutputConfig& o, double period) {
    const double dt = solver.time_step_for(period), duration = solver.duration_for(period);
    const double steps = std::ceil(duration / dt - 1e-9);
    if (double(o.decimation) > steps)
        s.fail("decimation", detail::concat("decimation = ", o.decimation, " steps is longer than the run (", steps,
                                            " steps): it would record a single row"));
    if (o.record_last_revolutions <= 0.0) return;
    if (o.record_last_revolutions * period > duration * (1.0 + 1e-12))
        s.fail("record_last_revolutions",
               detail::concat("record_last_revolutions = ", o.record_last_revolutions, " is longer than the run (",
                              duration / period, " revolutions)"));
    if (o.record_last_revolutions * period < 2.0 * double(o.decimation) * dt)
        s.fail("record_last_revolutions",
               detail::concat("record_last_revolutions = ", o.record_last_revolutions, " (",
                              o.record_last_revolutions * period, " s) holds fewer than two rows at decimation ",
                              o.decimation, " x time step ", dt, " s"));
}

// The element table ([[contact]], [[clearance]], ...) whose name the message quotes first ("clearance
// 'gap' ...", or 'g.bushing1' for a guide's bushing), if any.
std::optional<Section> element_named_in(const Section& root, const std::string& message) {
    std::optional<Section> found;
    std::size_t first = std::string::npos;
    for (const char* kind : {"dof", "shaft", "bearing", "drive", "motor", "spring", "damper", "spring_chain", "load",
                             "contact", "clearance", "guide"}) {
        for (const Section& s : root.tables(kind)) {
            if (!s.has("name")) continue;
            const std::string name = s.text("name");
            for (const std::string& quoted : {"'" + name + "'", "'" + name + "."}) {
                const std::size_t at = message.find(quoted);
                if (at < first) first = at, found.emplace(s);
            }
        }
    }
    return found;
}

}  // namespace

const MotionProgram& CaseConfig::program(const std::string& name) const {
    std::vector<std::string> known;
    for (const auto& [n, p] : programs) {
        if (n == name) return p;
        known.push_back(n);
    }
    detail::fail("unknown program '", detail::printable(name),
                 "'; the [program.<name>] tables define: ", detail::name_list(known));
}

CaseConfig build_case(const toml::table& table, const std::string& origin, const std::string& base_dir) {
    const Section root(table, "", std::make_shared<const std::string>(origin));
    CaseConfig c;
    c.origin = origin;
    Dimensions dims;
    Lengths lengths;
    for (auto& [name, s] : root.named_tables("program")) {
        NamedProgram p = read_program(s, base_dir);
        c.programs.emplace_back(name, std::move(p.program));
        dims[name] = p.dimension;
        lengths[name] = std::move(p.lengths);
    }
    double rpm = 0.0;
    std::optional<SpeedProgram> speed_program;
    if (const std::optional<Section> cam = root.table("camshaft")) {
        rpm = cam->quantity("speed", "rpm");
        // The model's own bounds (error.hpp), checked here so that the message names the line.
        const double lo = detail::min_camshaft_speed * 30.0 / pi, hi = detail::max_camshaft_speed * 30.0 / pi;
        if (!(rpm >= lo && rpm <= hi))
            cam->fail("speed", detail::concat("must be in [", lo, ", ", hi, "] rpm, got ", rpm));
        speed_program = read_speed_program(*cam, rpm);
        cam->finish({"speed", "run_up", "run_down", "modulation"});
    } else {
        root.fail_here("a [camshaft] table with its speed is required, e.g. [camshaft] speed = \"750 rpm\"");
    }
    const bool parts = root.has("dof") || root.has("contact") || root.has("spring") || root.has("shaft");
    if (const std::optional<Section> preset = root.table("preset")) {
        if (parts)
            root.fail(root.has("dof")       ? "dof"
                      : root.has("contact") ? "contact"
                                            : "spring",
                      "a [preset] mechanism is complete: describe the mechanism either by its parts or by a preset, "
                      "not both");
        c.preset = preset->text("name", "");
        c.mechanism = read_preset(*preset, c, dims, lengths, rpm);
    } else {
        if (!parts)
            root.fail_here("describe the mechanism: [[dof]], [[spring]], [[contact]] ... blocks, or a [preset]");
        read_parts(root, c, dims, lengths, c.mechanism);
        c.mechanism.set_camshaft_speed_rpm(rpm);
    }
    if (speed_program) c.mechanism.set_speed_program(*speed_program);
    if (const std::optional<Section> s = root.table("solver")) c.solver = read_solver(*s);
    if (const std::optional<Section> s = root.table("output")) {
        c.output = read_output(*s);
        check_recording(*s, c.solver, c.output, 60.0 / rpm);
    }
    // [sweep], [montecarlo] and [synthesis] describe studies run by the Python package (camfollower
    // sweep | montecarlo | synthesize), which reads and checks them; they do not change the case.
    (void)root.table("sweep");
    (void)root.table("montecarlo");
    (void)root.table("synthesis");
    root.finish({"camshaft",  "program", "preset",       "dof",     "spring",     "damper",  "load",     "contact",
                 "clearance", "guide",   "damping",      "gravity", "solver",     "output",  "shaft",    "bearing",
                 "drive",     "motor",   "spring_chain", "sweep",   "montecarlo", "linkage", "synthesis"});
    // The description must build (DOF references, contact geometry): fail now, located at the table
    // of the element the message names, else at the file (a fault of the whole structure).
    try {
        if (c.mechanism.structure.size() == presets::paper_dofs) (void)Mechanism<presets::paper_dofs>(c.mechanism);
        else (void)Mechanism<Eigen::Dynamic>(c.mechanism);
    } catch (const std::invalid_argument& e) {
        if (const std::optional<Section> s = element_named_in(root, e.what())) s->fail_named(e.what());
        detail::fail(origin, ": ", e.what());
    } catch (const ConvergenceError& e) {  // e.g. a static equilibrium that cannot be found
        throw ConvergenceError(detail::concat(detail::message_text(origin), ": ", e.what()));
    }
    return c;
}

CaseConfig parse_case(std::string_view text, const std::string& origin, const std::string& base_dir) {
    return build_case(parse_toml(text, origin), origin, base_dir);
}

CaseConfig load_case(const std::string& path) {
    struct stat st {};
    if (stat(path.c_str(), &st) != 0) detail::fail("config '", path, "': no such file");
    if (S_ISDIR(st.st_mode)) detail::fail("config '", path, "' is a directory, not a config file");
    if (!S_ISREG(st.st_mode)) detail::fail("config '", path, "' is not a regular file");
    if (st.st_size == 0) detail::fail("config '", path, "' is empty");
    if (st.st_size > (64 << 20))
        detail::fail("config '", path, "' is larger than 64 MiB; put large lift tables in a data file");
    std::ifstream in(path, std::ios::binary);
    if (!in) detail::fail("config '", path, "': cannot open for reading");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string::size_type slash = path.rfind('/');
    return parse_case(buffer.str(), path, slash == std::string::npos ? "." : path.substr(0, slash));
}

}  // namespace camfollower::config
