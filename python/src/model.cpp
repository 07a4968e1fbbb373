// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/model: parameters, defects, the 7-DOF model, modal analysis.
#include <cmath>
#include <optional>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/model/cam_follower_model.hpp"
#include "camfollower/model/modal.hpp"

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

void bind_model(py::module_& m) {
    py::class_<CamFollowerParameters> params(
        m, "Parameters",
        "Parameters of the 7-DOF model (SI units; paper Table 2 defaults). Override any by keyword:\n"
        "Parameters(contact_stiffness=2e8, camshaft_speed_rpm=1000). Parameters.names() lists them.");
    params.def(py::init(&parameters_from_kwargs))
        .def_static("names", &parameter_names)
        .def("get", &get_parameter, py::arg("name"),
             "The value of one of names(): a float (SI units), or the contact_damping model's name.")
        .def("replace", &with_kwargs,
             "A copy with the given parameters changed (validated); Parameters are immutable.")
        .def("to_dict", [](const CamFollowerParameters& p) {
            py::dict d;
            for (const auto& name : parameter_names()) d[name.c_str()] = get_parameter(p, name);
            return d;
        })
        .def_property_readonly("omega", &CamFollowerParameters::omega, "camshaft speed, rad/s")
        .def("__repr__", [](const CamFollowerParameters& p) {
            std::string s = "Parameters(";
            for (const auto& f : CamFollowerParameters::fields())
                s += detail::concat(f.name, "=", p.get(f.name), ", ");
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

    py::class_<Defects>(m, "Defects",
                        "Camshaft eccentricity and follower backlash (m; phase and switch width in rad). Both off "
                        "by default.")
        .def(py::init([](double eccentricity, double eccentricity_phase, double backlash, double width) {
                 Defects d{eccentricity, eccentricity_phase, backlash, width};
                 d.validate();
                 return d;
             }),
             py::arg("eccentricity") = 0.0, py::arg("eccentricity_phase") = 0.0, py::arg("backlash") = 0.0,
             py::arg("backlash_switch_width") = 0.0)
        .def_readonly("eccentricity", &Defects::eccentricity)
        .def_readonly("eccentricity_phase", &Defects::eccentricity_phase)
        .def_readonly("backlash", &Defects::backlash)
        .def_readonly("backlash_switch_width", &Defects::backlash_switch_width)
        .def("__repr__", [](const Defects& d) {
            return detail::concat("Defects(eccentricity=", d.eccentricity, ", eccentricity_phase=", d.eccentricity_phase,
                                  ", backlash=", d.backlash, ", backlash_switch_width=", d.backlash_switch_width, ")");
        });

    py::class_<CamFollowerModel>(
        m, "CamFollowerModel",
        "The paper's 7-DOF flexible cam-follower model. q = (y1, y2, y3, y4, x1, x2, x3): y along the\n"
        "follower axis, x across it; 1 camshaft, 2 roller, 3 follower rod, 4 follower top. Absolute\n"
        "displacements from the unloaded touching configuration (y2..y4 carry the lift h).")
        .def(py::init([](const std::optional<CamFollowerParameters>& p, const std::optional<MotionProgram>& program,
                         const std::optional<Defects>& defects) {
                 return CamFollowerModel(p.value_or(CamFollowerParameters{}),
                                         program.value_or(MotionProgram::paper_default()),
                                         defects.value_or(Defects{}));
             }),
             py::arg("parameters") = py::none(), py::arg("program") = py::none(), py::arg("defects") = py::none())
        .def_property_readonly("parameters", &CamFollowerModel::parameters, py::return_value_policy::copy)
        .def(
            "with_parameters",
            [](const CamFollowerModel& m, const py::kwargs& kwargs) {
                return CamFollowerModel(with_kwargs(m.parameters(), kwargs), m.cam().program(), m.defects());
            },
            "A new model with the given parameters changed (the model itself is immutable).")
        .def_property_readonly("defects", &CamFollowerModel::defects)
        .def_property_readonly("cam", &CamFollowerModel::cam)
        .def_property_readonly("mass_matrix", &CamFollowerModel::mass_matrix)
        .def_property_readonly("damping_matrix", &CamFollowerModel::damping_matrix)
        .def_property_readonly("stiffness_matrix", &CamFollowerModel::stiffness_matrix)
        .def_property_readonly("initial_state", &CamFollowerModel::initial_state,
                               "static equilibrium at t = 0 (m)")
        .def_property_readonly("omega", &CamFollowerModel::omega, "rad/s")
        .def_property_readonly("period", &CamFollowerModel::period, "one camshaft revolution, s")
        .def_property_readonly("spring_preload", &CamFollowerModel::spring_preload,
                               "P (N): return-spring force on y4 is -(P + K_rs y4)")
        .def_property_readonly_static("dof_names", [](py::object) {
            std::vector<std::string> names;
            for (int k = 0; k < CamFollowerModel::dofs; ++k) names.emplace_back(CamFollowerModel::dof_name(k));
            return names;
        })
        .def("static_equilibrium", &CamFollowerModel::static_equilibrium, py::arg("theta"),
             "Quasi-static equilibrium at cam angle theta (rad).")
        .def(
            "contact",
            [](const CamFollowerModel& model, double t, const CamFollowerModel::Vector& q,
               const CamFollowerModel::Vector& v) {
                for (int k = 0; k < CamFollowerModel::dofs; ++k) {
                    if (!(std::abs(q[k]) <= detail::max_part_length))
                        detail::fail("q[", k, "] (", CamFollowerModel::dof_name(k), ") must be in [",
                                     -detail::max_part_length, ", ", detail::max_part_length, "] m, got ", q[k]);
                    if (!std::isfinite(v[k]))
                        detail::fail("v[", k, "] (", CamFollowerModel::dof_name(k), ") must be finite (m/s), got ", v[k]);
                }
                const auto c = model.at_time(t);
                const auto n = model.nonlinear(c, q, v);
                py::dict d;
                d["penetration"] = n.delta;
                d["penetration_rate"] = n.delta_dot;
                d["force"] = n.contact.force;
                d["stiffness"] = n.contact.stiffness;
                d["in_contact"] = n.contact.in_contact;
                d["direction"] = CamFollowerModel::Vector(c.g);
                d["external_force"] = CamFollowerModel::Vector(c.external);
                d["pressure_angle"] = c.pressure_angle();
                d["nonlinear_force"] = CamFollowerModel::Vector(n.force);
                return d;
            },
            py::arg("t"), py::arg("q"), py::arg("v"),
            "Contact state at time t for displacements q and velocities v (diagnostics).")
        .def(
            "modal_analysis",
            [](const CamFollowerModel& model, double theta, bool with_contact) {
                const ModalResult r = modal_analysis(model, theta, with_contact);
                py::dict d;
                d["frequencies_hz"] = CamFollowerModel::Vector(r.frequencies_hz);
                d["mode_shapes"] = CamFollowerModel::Matrix(r.mode_shapes);
                d["tangent_stiffness"] = CamFollowerModel::Matrix(r.tangent_stiffness);
                d["contact_stiffness"] = r.contact_stiffness;
                return d;
            },
            py::arg("theta") = 0.0, py::arg("with_contact") = true,
            "Undamped natural frequencies (Hz, ascending) and mass-normalized mode shapes (columns) of the\n"
            "model linearized at the quasi-static equilibrium at cam angle theta (rad).");
}

}  // namespace camfollower::python
