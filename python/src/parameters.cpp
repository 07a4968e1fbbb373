// SPDX-License-Identifier: BSD-3-Clause
// Bindings for the paper preset's parameter card (model/presets/paper_parameters.hpp).
#include <cmath>
#include <optional>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/model/presets/paper_parameters.hpp"

namespace camfollower::python {

namespace {
constexpr const char* contact_damping_models = "'none', 'hunt_crossley' or 'lankarani_nikravesh'";

const char* contact_damping_name(ContactDampingModel model) {
    return model == ContactDampingModel::none            ? "none"
           : model == ContactDampingModel::hunt_crossley ? "hunt_crossley"
                                                         : "lankarani_nikravesh";
}

// One setter for every name Parameters.names() lists, used by the constructor, replace() and
// with_parameters(); the caller validates once all are set (order does not matter).
void assign_parameter(CamFollowerParameters& p, const std::string& name, const py::handle& value) {
    if (name == "contact_damping") {
        if (!py::isinstance<py::str>(value))
            throw py::type_error(detail::concat("contact_damping must be ", contact_damping_models, ", got ",
                                                std::string(py::str(py::type::handle_of(value).attr("__name__")))));
        const std::string model = py::str(value);
        if (model == "none") p.contact_damping = ContactDampingModel::none;
        else if (model == "hunt_crossley") p.contact_damping = ContactDampingModel::hunt_crossley;
        else if (model == "lankarani_nikravesh") p.contact_damping = ContactDampingModel::lankarani_nikravesh;
        else detail::fail("contact_damping must be ", contact_damping_models, ", got '", detail::printable(model), "'");
        return;
    }
    double& slot = p.ref(name);  // unknown names fail here, before the value is converted
    slot = number_argument(name, value);
}

CamFollowerParameters with_kwargs(CamFollowerParameters p, const py::kwargs& kwargs) {
    for (const auto& item : kwargs) assign_parameter(p, py::str(item.first), item.second);
    p.validate();
    return p;
}

CamFollowerParameters parameters_from_kwargs(const py::kwargs& kwargs) { return with_kwargs({}, kwargs); }

std::vector<std::string> parameter_names() {
    std::vector<std::string> names;
    for (const auto& f : CamFollowerParameters::fields()) names.emplace_back(f.name);
    names.emplace_back("contact_damping");
    return names;
}

py::object get_parameter(const CamFollowerParameters& p, const std::string& name) {
    if (name == "contact_damping") return py::str(contact_damping_name(p.contact_damping));
    return py::float_(p.get(name));
}
}  // namespace

void bind_parameters(py::module_& m) {
    py::class_<CamFollowerParameters> params(
        m, "Parameters",
        "The paper preset's parameters (SI units; paper Table 2 defaults; presets.paper(parameters)). Override any by "
        "keyword:\n"
        "Parameters(contact_stiffness=2e8, camshaft_speed_rpm=1000). Parameters.names() lists them.");
    params.def(py::init(&parameters_from_kwargs))
        .def_static("names", &parameter_names)
        .def("get", &get_parameter, py::arg("name"),
             "The value of one of names(): a float (SI units), or the contact_damping model's name.")
        .def("replace", &with_kwargs, "A copy with the given parameters changed (validated); Parameters are immutable.")
        .def("to_dict",
             [](const CamFollowerParameters& p) {
                 py::dict d;
                 for (const auto& name : parameter_names()) d[name.c_str()] = get_parameter(p, name);
                 return d;
             })
        .def_property_readonly("omega", &CamFollowerParameters::omega, "camshaft speed, rad/s")
        .def("__repr__", [](const CamFollowerParameters& p) {
            std::string s = "Parameters(";
            for (const auto& f : CamFollowerParameters::fields()) s += detail::concat(f.name, "=", p.get(f.name), ", ");
            return s + "contact_damping='" + contact_damping_name(p.contact_damping) + "')";
        });
    params.def_property_readonly(
        "contact_damping", [](const CamFollowerParameters& p) { return contact_damping_name(p.contact_damping); },
        "contact damping model: 'none', 'hunt_crossley' or 'lankarani_nikravesh'; read-only: use "
        "replace(contact_damping=...)");
    for (const auto& f : CamFollowerParameters::fields()) {
        const std::string name = f.name;
        params.def_property_readonly(
            f.name, [name](const CamFollowerParameters& p) { return p.get(name); },
            detail::concat(f.name, " (", f.unit, "); read-only: use replace(", f.name, "=...)").c_str());
    }
}

}  // namespace camfollower::python
