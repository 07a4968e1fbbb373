// SPDX-License-Identifier: BSD-3-Clause
// camfollower.SolverSettings: the C++ SolverSettings (solver/settings.hpp) as an immutable, picklable
// Python value with the C++ field names and defaults. Keywords are checked by name and type here, the
// values by SolverSettings::validate().
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/solver/settings.hpp"

namespace camfollower::python {

namespace {

const char* const field_names[] = {
    "method",        "time_step",          "tolerance",           "max_step",       "gamma",       "beta", "hht_alpha",
    "linear_solver", "residual_tolerance", "increment_tolerance", "max_iterations", "max_halvings"};

std::string listed_fields() {
    std::string list;
    for (const char* f : field_names) list += std::string(list.empty() ? "" : ", ") + f;
    return list;
}

// An integer: int or anything with __index__ (NumPy integers), never a bool.
int integer_argument(const std::string& name, const py::handle& value) {
    if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr()))
        throw py::type_error(name + " must be an integer, got " +
                             std::string(py::str(py::type::handle_of(value).attr("__name__"))));
    PyObject* index = PyNumber_Index(value.ptr());
    if (!index) throw py::error_already_set();
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(index, &overflow);
    Py_DECREF(index);
    if (overflow != 0 || x < -1000000 || x > 1000000)
        detail::fail(name, " must be an integer in [-1e6, 1e6], got ", std::string(py::str(value)));
    return int(x);
}

std::string text_argument(const std::string& name, const py::handle& value) {
    if (!py::isinstance<py::str>(value))
        throw py::type_error(name + " must be a str, got " +
                             std::string(py::str(py::type::handle_of(value).attr("__name__"))));
    return value.cast<std::string>();
}

// The settings from keywords (None: the default); gamma and beta given with any method but newmark,
// hht_alpha with any but hht, are refused, even at their default values.
SolverSettings settings_from_keywords(const py::dict& kw) {
    for (const auto& item : kw) {
        const std::string key = py::str(item.first);
        bool known = false;
        for (const char* f : field_names) known = known || key == f;
        if (!known)
            throw py::type_error("SolverSettings got an unexpected keyword '" + key +
                                 "'; its fields: " + listed_fields());
    }
    const auto given = [&kw](const char* key) { return kw.contains(key) && !kw[key].is_none(); };
    SolverSettings s;
    if (given("method")) s.method = method_from_name(text_argument("method", kw["method"]));
    check_newmark_parameters_apply(s.method, given("gamma") || given("beta"), given("hht_alpha"));
    const auto number = [&](const char* key, double& field) {
        if (given(key)) field = number_argument(key, kw[key]);
    };
    number("time_step", s.time_step);
    if (given("tolerance")) s.tolerance = number_argument("tolerance", kw["tolerance"]);
    number("max_step", s.max_step);
    number("gamma", s.gamma);
    number("beta", s.beta);
    if (given("hht_alpha")) s.hht_alpha = number_argument("hht_alpha", kw["hht_alpha"]);
    number("residual_tolerance", s.residual_tolerance);
    number("increment_tolerance", s.increment_tolerance);
    if (given("max_iterations")) s.max_iterations = integer_argument("max_iterations", kw["max_iterations"]);
    if (given("max_halvings")) s.max_halvings = integer_argument("max_halvings", kw["max_halvings"]);
    if (given("linear_solver")) set_linear_solver(s, text_argument("linear_solver", kw["linear_solver"]));
    s.validate();
    return s;
}

// The fields that say what these settings are: the method, the time step, and each other field that
// applies to the method and differs from its default (what repr shows and pickle keeps).
py::dict fields_of(const SolverSettings& s) {
    const SolverSettings d;
    py::dict f;
    f["method"] = method_name(s.method);
    f["time_step"] = s.time_step;
    if (s.tolerance) f["tolerance"] = *s.tolerance;
    if (s.max_step != d.max_step) f["max_step"] = s.max_step;
    if (s.method == Method::newmark && (s.gamma != d.gamma || s.beta != d.beta))
        f["gamma"] = s.gamma, f["beta"] = s.beta;
    if (s.method == Method::hht) f["hht_alpha"] = newmark_parameters(s).alpha;
    if (std::string(linear_solver_name(s)) != "auto") f["linear_solver"] = linear_solver_name(s);
    if (s.residual_tolerance != d.residual_tolerance) f["residual_tolerance"] = s.residual_tolerance;
    if (s.increment_tolerance != d.increment_tolerance) f["increment_tolerance"] = s.increment_tolerance;
    if (s.max_iterations != d.max_iterations) f["max_iterations"] = s.max_iterations;
    if (s.max_halvings != d.max_halvings) f["max_halvings"] = s.max_halvings;
    return f;
}

}  // namespace

void bind_settings(py::module_& m) {
    // The integration methods from the one table (solver/settings.hpp): name -> (order, summary).
    py::dict methods;
    for (const MethodTraits& t : method_table) methods[py::str(t.name)] = py::make_tuple(t.order, t.summary);
    m.attr("METHODS") = methods;
    m.attr("RUNGE_KUTTA_DEFAULT_TOLERANCE") = runge_kutta_default_tolerance;
    const SolverSettings d;
    py::class_<SolverSettings> cls(m, "SolverSettings", R"doc(
The integration settings of simulate(), simulate_many() and periodic_steady_state(), immutable.

``SolverSettings(method="newmark", **fields)``, the fields (``SolverSettings.FIELDS``) and their
defaults those of the C++ SolverSettings (docs/solvers.md): ``time_step`` 3e-6 s, ``tolerance``
None, ``max_step`` 0 (unbounded), ``gamma`` 1/2, ``beta`` 1/4, ``hht_alpha``, ``linear_solver``
"auto", ``residual_tolerance`` and ``increment_tolerance`` 1e-10, ``max_iterations`` 25,
``max_halvings`` 6. ``method``: a name of ``camfollower.METHODS``. A run is error-controlled exactly
when ``tolerance`` is set (``time_step`` is then the output interval); the Runge-Kutta methods run
under 1e-6 when none is set. ``gamma``/``beta`` apply to "newmark" only and ``hht_alpha`` to "hht"
only (default -0.05): given with another method they are refused. ``replace(**changes)`` returns a
copy with fields changed (changing the method drops gamma, beta and hht_alpha unless given again).
Raises ValueError for a value out of range, TypeError for an unknown keyword or a wrong type.
)doc");
    cls.def_property_readonly_static(
        "FIELDS",
        [](const py::object&) {
            py::tuple names(std::size(field_names));
            for (std::size_t k = 0; k < std::size(field_names); ++k) names[k] = field_names[k];
            return names;
        },
        "The field names, in the C++ order.");
    cls.def(py::init([](const py::object& method, const py::kwargs& kw) {
                py::dict all(kw);
                if (all.contains("method"))
                    throw py::type_error("SolverSettings got method twice (positional and keyword)");
                all["method"] = method;
                return settings_from_keywords(all);
            }),
            py::arg("method") = method_name(d.method))
        .def_property_readonly("method", [](const SolverSettings& s) { return std::string(method_name(s.method)); })
        .def_property_readonly(
            "time_step", [](const SolverSettings& s) { return s.time_step; },
            "s; under a tolerance the output interval")
        .def_property_readonly(
            "tolerance", [](const SolverSettings& s) { return s.tolerance; }, "None: fixed steps")
        .def_property_readonly(
            "max_step", [](const SolverSettings& s) { return s.max_step; }, "s, 0: unbounded")
        .def_property_readonly(
            "gamma", [](const SolverSettings& s) { return newmark_parameters(s).gamma; },
            "Newmark's gamma as the method steps with it")
        .def_property_readonly(
            "beta", [](const SolverSettings& s) { return newmark_parameters(s).beta; },
            "Newmark's beta as the method steps with it")
        .def_property_readonly(
            "hht_alpha", [](const SolverSettings& s) { return newmark_parameters(s).alpha; },
            "HHT's alpha as the method steps with it (0 but for method 'hht')")
        .def_property_readonly("linear_solver",
                               [](const SolverSettings& s) { return std::string(linear_solver_name(s)); })
        .def_property_readonly("residual_tolerance", [](const SolverSettings& s) { return s.residual_tolerance; })
        .def_property_readonly("increment_tolerance", [](const SolverSettings& s) { return s.increment_tolerance; })
        .def_property_readonly("max_iterations", [](const SolverSettings& s) { return s.max_iterations; })
        .def_property_readonly("max_halvings", [](const SolverSettings& s) { return s.max_halvings; })
        .def_property_readonly(
            "adaptive", [](const SolverSettings& s) { return s.adaptive() || is_runge_kutta(s.method); },
            "True when the run adapts its steps: a tolerance set, or a Runge-Kutta method "
            "(which runs under 1e-6 without one)")
        .def("fields", &fields_of,
             "The fields that say what these settings are (method, time step, and the others "
             "that apply and differ from their defaults), as keywords of SolverSettings.")
        .def("replace",
             [](const SolverSettings& s, const py::kwargs& changes) {
                 py::dict kw = fields_of(s);
                 if (changes.contains("method") &&
                     py::str(changes["method"]).cast<std::string>() != method_name(s.method))
                     for (const char* k : {"gamma", "beta", "hht_alpha"})
                         if (kw.contains(k)) PyDict_DelItemString(kw.ptr(), k);
                 for (const auto& item : changes) kw[item.first] = item.second;
                 return settings_from_keywords(kw);
             })
        .def(
            "__eq__", [](const SolverSettings& a, const SolverSettings& b) { return fields_of(a).equal(fields_of(b)); },
            py::is_operator())
        .def("__hash__", [](const SolverSettings& s) { return py::hash(py::tuple(fields_of(s).attr("items")())); })
        .def("__repr__",
             [](const SolverSettings& s) {
                 std::string out = "SolverSettings(";
                 bool first = true;
                 for (const auto& item : fields_of(s)) {
                     out += std::string(first ? "" : ", ") + std::string(py::str(item.first)) + "=" +
                            std::string(py::repr(item.second));
                     first = false;
                 }
                 return out + ")";
             })
        .def(py::pickle([](const SolverSettings& s) { return fields_of(s); },
                        [](const py::dict& kw) { return settings_from_keywords(kw); }));
}

}  // namespace camfollower::python
