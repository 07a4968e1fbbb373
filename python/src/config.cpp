// SPDX-License-Identifier: BSD-3-Clause
// Config files for Python: the same reader as the command line (src/config, toml++), so a config
// means the same in both. Python parses with tomllib and hands the dict over (converted to a toml++
// table); the text route keeps line numbers in the messages.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "config/case_from_table.hpp"
#include "config/section.hpp"

namespace camfollower::python {

namespace {

// A Python value from tomllib (dict, list, str, bool, int, float) as a toml++ node.
void insert(toml::table& t, const std::string& key, const py::handle& v, const std::string& path);

void append(toml::array& a, const py::handle& v, const std::string& path) {
    if (py::isinstance<py::bool_>(v)) a.push_back(v.cast<bool>());
    else if (py::isinstance<py::int_>(v)) a.push_back(v.cast<int64_t>());
    else if (py::isinstance<py::float_>(v)) a.push_back(v.cast<double>());
    else if (py::isinstance<py::str>(v)) a.push_back(v.cast<std::string>());
    else if (py::isinstance<py::dict>(v)) {
        toml::table sub;
        for (const auto& [k, x] : v.cast<py::dict>()) insert(sub, py::str(k), x, path);
        a.push_back(std::move(sub));
    } else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
        toml::array sub;
        for (const auto& x : v) append(sub, x, path);
        a.push_back(std::move(sub));
    } else {
        detail::fail(path, ": a config value must be a str, bool, int, float, list or dict, got ", std::string(py::str(py::type::handle_of(v))));
    }
}

void insert(toml::table& t, const std::string& key, const py::handle& v, const std::string& parent) {
    const std::string path = parent.empty() ? key : parent + "." + key;
    if (py::isinstance<py::dict>(v)) {
        toml::table sub;
        for (const auto& [k, x] : v.cast<py::dict>()) insert(sub, py::str(k), x, path);
        t.insert(key, std::move(sub));
        return;
    }
    toml::array one;
    append(one, v, path);
    t.insert(key, std::move(*one.get(0)));
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
    const std::string method = method_name(s.newmark);
    if (method == "newmark") {
        solver["gamma"] = s.newmark.gamma;
        solver["beta"] = s.newmark.beta;
        solver["hht_alpha"] = s.newmark.hht_alpha;
    } else {
        solver["method"] = method;
    }
    if (uses_tolerance(s.newmark.method)) {
        solver["tolerance"] = s.newmark.tolerance;
        solver["max_step"] = s.newmark.max_step;
    }
    solver["linear_solver"] = linear_solver_name(s.newmark);
    solver["residual_tolerance"] = s.newmark.residual_tolerance;
    solver["increment_tolerance"] = s.newmark.increment_tolerance;
    solver["max_iterations"] = s.newmark.max_iterations;
    solver["max_halvings"] = s.newmark.max_halvings;
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

}  // namespace

void bind_config(py::module_& m) {
    m.def(
        "_case_from_text",
        [](const std::string& text, const std::string& origin, const std::string& base_dir) {
            return to_python(config::parse_case(text, origin, base_dir));
        },
        py::arg("text"), py::arg("origin"), py::arg("base_dir"));
    m.def(
        "_case_from_dict",
        [](const py::dict& data, const std::string& origin, const std::string& base_dir) {
            toml::table root;
            for (const auto& [k, v] : data) insert(root, py::str(k), v, "");
            return to_python(config::build_case(root, origin, base_dir));
        },
        py::arg("data"), py::arg("origin"), py::arg("base_dir"));
}

}  // namespace camfollower::python
