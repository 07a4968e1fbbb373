// SPDX-License-Identifier: BSD-3-Clause
// Config files for Python: the same reader as the command line (src/config, toml++), so a config
// means the same in both. A file is parsed by toml++ for Python too (load_config's `data` is that
// table as a dict): one parser, one answer on every input (a byte order mark, deep nesting, a long
// dotted key), with line numbers in every message. A dict (config_from_dict) is converted to a toml++
// table, bounded in depth (config::max_nesting) and in repeats of one object, so a cyclic dict, or
// shared sub-dicts that would expand to billions of values, are refused at once.
#include <algorithm>
#include <climits>
#include <cmath>
#include <unordered_map>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "config/case_from_table.hpp"
#include "config/force_closure.hpp"
#include "config/section.hpp"

namespace camfollower::python {

namespace {

// How often one dict or list object may appear in a config's tree: sharing a sub-dict (one follower
// table in two contacts) is fine, but shared sub-dicts nested in each other reach billions of values
// in a few dozen levels, well within the depth bound; this ends that at once.
constexpr int max_repeats = 1000;

// ---- Python dict -> toml++ table (config_from_dict) --------------------------------------------

class FromPython {
public:
    explicit FromPython(std::string origin) : origin_(std::move(origin)), datetime_(py::module_::import("datetime")) {}

    toml::table table(const py::handle& d, int depth) {
        if (depth > config::max_nesting) config::fail_nesting(origin_, 0, parts_);
        repeated(d);
        toml::table t;
        for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(d)) {
            if (!py::isinstance<py::str>(k))
                fail(detail::concat("keys must be strings (TOML keys), got ", type_name(k), " ", repr(k)));
            const std::string key = utf8(k, "a key");
            parts_.push_back(key);
            value(v, depth + 1, IntoTable{t, key});
            parts_.pop_back();
        }
        return t;
    }

private:
    [[noreturn]] void fail(const std::string& message) const {
        detail::fail(origin_, parts_.empty() ? "" : ": ", config::key_path_text(parts_), ": ", message);
    }
    static std::string type_name(const py::handle& v) { return py::str(py::type::handle_of(v).attr("__name__")); }
    static std::string repr(const py::handle& v) { return detail::printable(std::string(py::repr(v)), 40); }

    void repeated(const py::handle& container) {
        if (++seen_[container.ptr()] > max_repeats)
            fail(detail::concat("this ", type_name(container), " object appears more than ", max_repeats,
                                " times in the config (shared sub-dicts nested in each other?)"));
    }

    std::string utf8(const py::handle& s, const char* what) const {
        Py_ssize_t size = 0;
        const char* data = PyUnicode_AsUTF8AndSize(s.ptr(), &size);
        if (!data) {
            PyErr_Clear();
            fail(detail::concat(what, " must be valid Unicode text (no lone surrogates), got ", repr(s)));
        }
        return std::string(data, std::size_t(size));
    }

    // Where a converted value goes: two sink types only, so value() has two instantiations (a lambda
    // made inside value() would be a new type per level: unbounded template recursion at compile time).
    struct IntoTable {
        toml::table& t;
        const std::string& key;
        template <class X>
        void operator()(X&& x) const {
            t.insert_or_assign(key, std::forward<X>(x));
        }
    };
    struct IntoArray {
        toml::array& a;
        template <class X>
        void operator()(X&& x) const {
            a.push_back(std::forward<X>(x));
        }
    };

    template <class Add>
    void value(const py::handle& v, int depth, const Add& add) {
        if (py::isinstance<py::bool_>(v)) return add(toml::value<bool>(v.cast<bool>()));
        if (py::isinstance<py::int_>(v)) {
            int overflow = 0;
            const long long i = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
            if (overflow) fail(detail::concat("the integer ", repr(v), " does not fit in 64 bits (TOML integers)"));
            return add(toml::value<int64_t>(int64_t(i)));
        }
        if (py::isinstance<py::float_>(v)) return add(toml::value<double>(v.cast<double>()));
        if (py::isinstance<py::str>(v)) return add(toml::value<std::string>(utf8(v, "a string")));
        if (py::isinstance<py::dict>(v)) return add(table(v, depth));
        if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
            if (depth > config::max_nesting) config::fail_nesting(origin_, 0, parts_);
            repeated(v);
            toml::array a;
            std::size_t i = 0;
            for (const auto& x : v) {
                parts_.push_back(detail::concat("[", i++, "]"));
                value(x, depth + 1, IntoArray{a});
                parts_.pop_back();
            }
            return add(std::move(a));
        }
        // Dates and times, as load_config's data holds them (a config never uses one; the reader names it).
        if (py::isinstance(v, datetime_.attr("datetime"))) {
            toml::date_time dt{date(v), time(v)};
            const py::object offset = v.attr("utcoffset")();
            if (!offset.is_none())
                dt.offset = toml::time_offset{0, int(offset.attr("total_seconds")().cast<double>() / 60.0)};
            return add(toml::value<toml::date_time>(dt));
        }
        if (py::isinstance(v, datetime_.attr("date"))) return add(toml::value<toml::date>(date(v)));
        if (py::isinstance(v, datetime_.attr("time"))) return add(toml::value<toml::time>(time(v)));
        fail(detail::concat("a config value must be a str, bool, int, float, list, dict or a date/time, got ",
                            type_name(v)));
    }
    static toml::date date(const py::handle& v) {
        return {uint16_t(v.attr("year").cast<int>()), uint8_t(v.attr("month").cast<int>()),
                uint8_t(v.attr("day").cast<int>())};
    }
    static toml::time time(const py::handle& v) {
        return {uint8_t(v.attr("hour").cast<int>()), uint8_t(v.attr("minute").cast<int>()),
                uint8_t(v.attr("second").cast<int>()), uint32_t(v.attr("microsecond").cast<int>()) * 1000u};
    }

    std::string origin_;
    py::module_ datetime_;
    std::vector<std::string> parts_;
    std::unordered_map<const PyObject*, int> seen_;  // the objects stay alive: the dict holds them
};

// ---- toml++ table -> Python (load_config's data) ----------------------------------------------

class ToPython {
public:
    explicit ToPython(std::string origin) : origin_(std::move(origin)), datetime_(py::module_::import("datetime")) {}

    // Recursion is bounded: parse_toml refused anything deeper than config::max_nesting.
    py::object convert(const toml::node& n) {
        if (const toml::table* t = n.as_table()) {
            // In the file's order (toml++ keeps keys sorted), as tomllib gave them.
            std::vector<std::pair<std::string_view, const toml::node*>> entries;
            for (auto&& [k, v] : *t) entries.emplace_back(k.str(), &v);
            std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
                const toml::source_position pa = a.second->source().begin, pb = b.second->source().begin;
                return pa.line != pb.line ? pa.line < pb.line : pa.column < pb.column;
            });
            py::dict d;
            for (const auto& [k, v] : entries) {
                parts_.emplace_back(k);
                d[py::str(k.data(), k.size())] = convert(*v);
                parts_.pop_back();
            }
            return py::object(std::move(d));
        }
        if (const toml::array* a = n.as_array()) {
            py::list l;
            for (std::size_t i = 0; i < a->size(); ++i) {
                parts_.push_back(detail::concat("[", i, "]"));
                l.append(convert(*a->get(i)));
                parts_.pop_back();
            }
            return py::object(std::move(l));
        }
        if (const auto* s = n.as_string()) return py::str(s->get());
        if (const auto* i = n.as_integer()) return py::int_(i->get());
        if (const auto* x = n.as_floating_point()) return py::float_(x->get());
        if (const auto* b = n.as_boolean()) return py::bool_(b->get());
        try {
            if (const auto* d = n.as_date()) return date(d->get());
            if (const auto* t = n.as_time()) return time(t->get(), py::none());
            const toml::date_time dt = n.as_date_time()->get();
            py::object tz = py::none();
            if (dt.offset)
                tz = datetime_.attr("timezone")(datetime_.attr("timedelta")(py::arg("minutes") = dt.offset->minutes));
            return datetime_.attr("datetime")(dt.date.year, dt.date.month, dt.date.day, dt.time.hour, dt.time.minute,
                                              dt.time.second, dt.time.nanosecond / 1000u, tz);
        } catch (const py::error_already_set& e) {  // year 0, a leap second: valid TOML, not a Python date
            const std::size_t line = n.source().begin.line;
            detail::fail(line ? detail::concat(origin_, ":", line) : origin_, ": ", config::key_path_text(parts_),
                         ": a date or time Python cannot hold (", e.what(), ")");
        }
    }

private:
    py::object date(const toml::date& d) const { return datetime_.attr("date")(d.year, d.month, d.day); }
    py::object time(const toml::time& t, const py::object& tz) const {
        return datetime_.attr("time")(t.hour, t.minute, t.second, t.nanosecond / 1000u, tz);
    }

    std::string origin_;
    py::module_ datetime_;
    std::vector<std::string> parts_;
};

// The line of the value at `path` (keys and indices) in the TOML text, or of its deepest part that
// exists; None for text that does not parse or a path not there at all. For the Python-side tables
// ([sweep], [montecarlo]), whose messages name file, line and key as the reader's do.
py::object toml_line(const std::string& text, const py::list& path) {
    toml::table root;
    try {
        root = config::parse_toml(text, "<text>");
    } catch (const std::invalid_argument&) {
        return py::none();
    }
    const toml::node* node = &root;
    std::size_t line = 0;
    for (const py::handle& part : path) {
        const toml::node* next = nullptr;
        if (py::isinstance<py::int_>(part)) {
            const toml::array* a = node->as_array();
            const long long i = part.cast<long long>();
            if (a && i >= 0 && std::size_t(i) < a->size()) next = a->get(std::size_t(i));
        } else if (const toml::table* t = node->as_table()) {
            next = t->get(part.cast<std::string>());
        }
        if (!next) break;
        node = next;
        if (node->source().begin.line > 0) line = node->source().begin.line;
    }
    return line > 0 ? py::object(py::int_(line)) : py::object(py::none());
}

py::dict to_python(const config::CaseConfig& c) {
    py::dict programs;
    for (const auto& [name, p] : c.programs) programs[py::str(name)] = p;
    const config::SolverConfig& s = c.solver;
    py::dict solver;
    if (s.duration > 0.0) solver["duration"] = s.duration;
    else solver["revolutions"] = s.revolutions;
    if (s.time_step > 0.0) solver["time_step"] = s.time_step;
    else solver["steps_per_revolution"] = s.steps_per_revolution;
    const SolverSettings& n = s.settings;
    solver["method"] = method_name(n.method);
    if (n.method == Method::newmark && (n.gamma != SolverSettings{}.gamma || n.beta != SolverSettings{}.beta)) {
        solver["gamma"] = n.gamma;
        solver["beta"] = n.beta;
    }
    if (n.method == Method::hht) solver["hht_alpha"] = newmark_parameters(n).alpha;
    if (n.tolerance) {
        solver["tolerance"] = *n.tolerance;
        solver["max_step"] = n.max_step;
    }
    solver["linear_solver"] = linear_solver_name(n);
    solver["residual_tolerance"] = n.residual_tolerance;
    solver["increment_tolerance"] = n.increment_tolerance;
    solver["max_iterations"] = n.max_iterations;
    solver["max_halvings"] = n.max_halvings;
    if (s.settle) {
        solver["settle"] = true;
        solver["settle_tolerance"] = s.settle_tolerance;
        if (!s.settle_dofs.empty()) solver["settle_dofs"] = s.settle_dofs;
        solver["settle_min_revolutions"] = s.settle_min_revolutions;
        solver["settle_max_revolutions"] = s.settle_max_revolutions;
    }
    py::dict output;
    output["file"] = c.output.file;
    output["decimation"] = c.output.decimation;
    if (c.output.record_last_revolutions > 0.0) output["record_last_revolutions"] = c.output.record_last_revolutions;
    py::dict d;
    d["origin"] = c.origin;
    d["preset"] = c.preset;
    d["programs"] = programs;
    d["builder"] = c.mechanism;
    d["solver"] = solver;
    d["output"] = output;
    return d;
}

// The force-closure checks (config/force_closure.hpp) as a dict; angles in degrees of each cam.
py::dict force_closure(const MechanismBuilder& b, double rpm) {
    const config::ForceClosure r = [&] {
        py::gil_scoped_release release;
        return config::check_force_closure(b, rpm);
    }();
    const auto deg = [](double rad) {
        const double d = std::fmod(radians_to_degrees(rad), 360.0);
        return d < 0.0 ? d + 360.0 : d;
    };
    const auto intervals = [&](const std::vector<std::pair<double, double>>& v) {
        py::list out;
        for (const auto& [a, z] : v) out.append(py::make_tuple(deg(a), deg(z)));
        return out;
    };
    py::list contacts;
    for (const config::ContactClosure& c : r.contacts) {
        py::dict d;
        d["contact"] = c.contact;
        d["static_min_force_N"] = c.static_min_force;
        d["static_min_angle_deg"] = deg(c.static_min_angle);
        d["static_open_deg"] = intervals(c.static_open);
        d["rigid_min_force_N"] = c.rigid_min_force;
        d["rigid_min_angle_deg"] = deg(c.rigid_min_angle);
        d["rigid_loss_deg"] = intervals(c.rigid_loss);
        d["rigid_limit_rpm"] = c.rigid_limit_rpm;
        d["grooved"] = c.grooved;
        d["outer_flank_deg"] = intervals(c.outer_flank);
        d["flank_changes"] = c.flank_changes;
        if (!c.conjugate.empty()) {
            d["conjugate"] = c.conjugate;
            d["other_cam_deg"] = intervals(c.other_cam);
        }
        contacts.append(d);
    }
    py::dict out;
    out["rpm"] = r.rpm;
    out["angles"] = r.angles;
    out["contacts"] = contacts;
    out["warnings"] = r.warnings;
    return out;
}

}  // namespace

void bind_config(py::module_& m) {
    m.def(
        "_read_config",
        [](const py::bytes& text, const std::string& origin, const std::string& base_dir) {
            const toml::table root = config::parse_toml(std::string(text), origin);
            py::object data = ToPython(origin).convert(root);
            return py::make_tuple(data, to_python(config::build_case(root, origin, base_dir)));
        },
        py::arg("text"), py::arg("origin"), py::arg("base_dir"));
    m.def(
        "_parse_toml",
        [](const py::bytes& text, const std::string& origin) {
            return ToPython(origin).convert(config::parse_toml(std::string(text), origin));
        },
        py::arg("text"), py::arg("origin"));
    m.def("_force_closure", &force_closure, py::arg("builder"), py::arg("rpm") = 0.0);
    m.def(
        "_toml_line", [](const py::bytes& text, const py::list& path) { return toml_line(std::string(text), path); },
        py::arg("text"), py::arg("path"));
    m.def(
        "_case_from_dict",
        [](const py::dict& data, const std::string& origin, const std::string& base_dir) {
            const toml::table root = FromPython(origin).table(data, 0);
            return to_python(config::build_case(root, origin, base_dir));
        },
        py::arg("data"), py::arg("origin"), py::arg("base_dir"));
}

}  // namespace camfollower::python
