// SPDX-License-Identifier: BSD-3-Clause
// Bindings for the open mechanism core: follower types, the mechanism builder, the immutable
// Mechanism (fixed-size Eigen up to 8 DOFs, dynamic above), the paper preset. Everything pickles.
#include <cctype>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/mechanism_modes.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/model/presets/valve_train.hpp"
#include "camfollower/solver/step_limit.hpp"
#include "camfollower/synthesis/lift_samples.hpp"
#include "run.hpp"

namespace camfollower::python {

namespace {
// The Python class names of the follower types ("TranslatingRoller, ..."), for messages.
template <class... F>
std::string class_names(const std::variant<F...>*) {
    std::string out;
    ((out += (out.empty() ? "" : ", ") + std::string(py::str(py::type::of<F>().attr("__name__")))), ...);
    return out;
}
// The first follower type that f is an instance of, or nothing.
template <class... F>
std::optional<Follower> cast_follower(const py::handle& f, const std::variant<F...>*) {
    std::optional<Follower> out;
    static_cast<void>(((py::isinstance<F>(f) && (out = f.cast<F>(), true)) || ...));
    return out;
}
}  // namespace

// std::variant of types without a default constructor has no pybind11 caster: every alternative of
// Follower (contact/contact_pair.hpp) in turn.
Follower follower_from(const py::handle& f) {
    const Follower* types = nullptr;
    if (std::optional<Follower> out = cast_follower(f, types)) return *std::move(out);
    detail::fail("follower must be one of ", class_names(types), "; got ", std::string(py::str(py::type::of(f))));
}

// One Python type for every mechanism: the paper preset keeps its fixed-size fast path (its size is
// known at compile time), other mechanisms are dynamic-size. More fixed sizes cost compile time
// (minutes each) for a few tens of percent of speed on small models.
class AnyMechanism {
public:
    using Variant = std::variant<Mechanism<presets::paper_dofs>, Mechanism<Eigen::Dynamic>>;

    explicit AnyMechanism(Variant m) : m_(std::move(m)) {}
    // A description of the preset's size runs on its fixed-size path (so a pickled preset, rebuilt from
    // its description, integrates bit for bit as the original).
    static AnyMechanism build(const MechanismBuilder& b) {
        AnyMechanism a = b.structure.size() == presets::paper_dofs ? AnyMechanism(Mechanism<presets::paper_dofs>(b))
                                                                   : AnyMechanism(Mechanism<Eigen::Dynamic>(b));
        a.warn();
        return a;
    }
    // The model's formulation warnings (Mechanism::warnings) as Python UserWarnings.
    void warn() const {
        const std::vector<std::string> warnings = std::visit([](const auto& x) { return x.warnings(); }, m_);
        for (const std::string& w : warnings)
            if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 2) != 0) throw py::error_already_set();
    }
    template <class F>
    decltype(auto) visit(F&& f) const {
        return std::visit(std::forward<F>(f), m_);
    }

private:
    Variant m_;
};

namespace {

// A follower parameter's value (follower/parameters.hpp) to and from Python: a turn by its name,
// a point as a length-2 array.
template <class T>
using python_parameter = std::conditional_t<std::is_same_v<T, ArmTurn>, py::object, T>;
template <class T>
T parameter_from_python(const python_parameter<T>& v) {
    if constexpr (std::is_same_v<T, ArmTurn>) return turn_argument(v);
    else return v;
}
template <class T>
auto parameter_to_python(const T& v) {
    if constexpr (std::is_same_v<T, ArmTurn>) return std::string(arm_turn_name(v));
    else return T(v);
}
// "pivot=(0.1, 0.05)": a point as a tuple, so that the repr reads back.
template <class T>
std::string parameter_repr(const T& v) {
    if constexpr (std::is_same_v<T, Eigen::Vector2d>) return std::string(py::repr(py::make_tuple(v.x(), v.y())));
    else return std::string(py::repr(py::cast(parameter_to_python(v))));
}

// The keyword argument of F's I-th parameter, with its default.
template <class F, std::size_t I>
auto parameter_argument() {
    constexpr FollowerParameter p = F::parameters[I];
    if constexpr (p.required) return py::arg(p.name);
    else if constexpr (p.kind == ParameterKind::turn)
        return py::arg_v(p.name, arm_turn_name(ArmTurn::counter_clockwise));
    else return py::arg_v(p.name, p.default_value);
}

// "translating_roller" -> "TranslatingRoller".
std::string class_name_of(std::string_view type_name) {
    std::string out;
    bool upper = true;
    for (char ch : type_name) {
        if (ch == '_') {
            upper = true;
            continue;
        }
        out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(ch))) : ch;
        upper = false;
    }
    return out;
}

template <class F, class = void>
struct has_start_angle : std::false_type {};
template <class F>
struct has_start_angle<F, std::void_t<decltype(std::declval<const F&>().start_angle())>> : std::true_type {};

// Constructor, read-only properties, pickling and repr of F, all from its parameter description.
template <class F, std::size_t... I>
void bind_parameters(py::class_<F>& c, std::index_sequence<I...>) {
    c.def(py::init([](const python_parameter<follower_parameter_type<F, I>>&... v) {
              return F(parameter_from_python<follower_parameter_type<F, I>>(v)...);
          }),
          parameter_argument<F, I>()...);
    (c.def_property_readonly(
         F::parameters[I].name, [](const F& f) { return parameter_to_python(std::get<I>(f.parameter_values())); },
         F::parameters[I].meaning),
     ...);
    c.def(py::pickle(
        [](const F& f) {
            const auto values = f.parameter_values();
            return py::make_tuple(parameter_to_python(std::get<I>(values))...);
        },
        [](const py::tuple& t) {
            if (t.size() != sizeof...(I))
                detail::fail(F::type_name, ": ", sizeof...(I), " pickled values expected, got ", t.size());
            return F(parameter_from_python<follower_parameter_type<F, I>>(
                t[I].template cast<python_parameter<follower_parameter_type<F, I>>>())...);
        }));
    c.def("__repr__", [](const F& f) {
        const auto values = f.parameter_values();
        std::string out = class_name_of(F::type_name) + "(";
        ((out += std::string(I == 0 ? "" : ", ") + F::parameters[I].name + "=" + parameter_repr(std::get<I>(values))),
         ...);
        return out + ")";
    });
}

template <class F>
void bind_follower(py::module_& m) {
    const std::string name = class_name_of(F::type_name);
    py::class_<F> c(m, name.c_str(), F::description);
    bind_parameters(c, std::make_index_sequence<F::parameters.size()>{});
    // Class attributes: its lift is a length (m) when translating, else the arm's rotation (rad).
    c.attr("translating") = F::translating;
    c.attr("type_name") = F::type_name;
    if constexpr (has_start_angle<F>::value)
        c.def_property_readonly("start_angle", &F::start_angle,
                                "start angle phi0 (rad, ground frame) of the arm at zero lift (a disk cam's: the "
                                "roller on the base circle)");
    c.def(
         "contact",
         [](const F& f, const MotionProgram& program, double theta) {
             const ContactGeometry g = f.contact(theta, program.evaluate(theta));
             py::dict d;
             d["normal"] = Eigen::Vector2d(g.normal);
             d["dnormal"] = Eigen::Vector2d(g.dnormal);
             d["lever"] = g.lever;
             d["dlever"] = g.dlever;
             d["lift"] = g.lift;
             d["dlift"] = g.dlift;
             d["pressure_angle"] = g.pressure_angle();
             return d;
         },
         py::arg("program"), py::arg("theta"),
         "Contact geometry at cam angle theta (rad): unit normal (ground frame), lever, lift and their theta-rates.")
        .def(
            "profile",
            [](const F& f, const MotionProgram& program, const DoubleArray& theta) {
                return map_to_dict<8>(theta,
                                      {"surface_x", "surface_y", "reference_x", "reference_y", "contact_x", "contact_y",
                                       "surface_radius", "pressure_angle"},
                                      [&](double t) {
                                          const FollowerProfilePoint p = f.profile(t, program.evaluate(t));
                                          return std::array<double, 8>{p.surface.x(),        p.surface.y(),
                                                                       p.reference.x(),      p.reference.y(),
                                                                       p.contact_ground.x(), p.contact_ground.y(),
                                                                       p.surface_radius,     p.pressure_angle};
                                      });
            },
            py::arg("program"), py::arg("theta"),
            "Cam profile at theta (rad, scalar or array): surface and reference points in the cam frame (m), the\n"
            "contact point in the ground frame (m), surface radius of curvature (m, > 0 convex), pressure angle.")
        .def(
            "max_pressure_angle",
            [](const F& f, const MotionProgram& program) {
                const AngleExtremum e = max_pressure_angle(program, f);
                return std::make_pair(e.theta, e.value);
            },
            py::arg("program"), "(theta, alpha) in rad of the largest |pressure angle| over the revolution.")
        .def(
            "min_surface_radius",
            [](const F& f, const MotionProgram& program) {
                const AngleExtremum e = min_surface_radius(program, f);
                return std::make_pair(e.theta, e.value);
            },
            py::arg("program"), "(theta, radius) of the smallest convex cam-surface radius of curvature (m).")
        .def(
            "check", [](const F& f, const MotionProgram& program) { check_undercut(program, f); }, py::arg("program"),
            "Raise ValueError naming the cam angle if the cam undercuts, has a cusp or the pressure angle reaches 90 "
            "deg.");
}

template <class... F>
void bind_followers(py::module_& m, const std::variant<F...>*) {
    (bind_follower<F>(m), ...);
}

py::object follower_to_python(const Follower& f) {
    return std::visit([](const auto& x) { return py::cast(x); }, f);
}

// Builder state as plain, self-describing Python data (pickling, and Mechanism.__reduce__).
py::dict builder_state(const MechanismBuilder& b) {
    py::list dofs, springs, loads, contacts, masses;
    // DOFs in order; a shaft's DOFs as one entry describing the shaft, where they start.
    const std::vector<DofSpec>& all = b.structure.dofs();
    for (std::size_t k = 0; k < all.size(); ++k) {
        const ShaftEntry* shaft = nullptr;
        for (const ShaftEntry& e : b.structure.shafts())
            if (e.first_dof == int(k)) shaft = &e;
        if (shaft) {
            const ShaftSpec& sp = shaft->spec;
            const BeamSection& sec = sp.section;
            dofs.append(py::dict(
                py::arg("shaft") = sp.name, py::arg("length") = sp.length,
                py::arg("max_element_length") = sp.max_element_length, py::arg("stations") = sp.stations,
                py::arg("axial") = sp.axial, py::arg("damping") = sp.damping,
                py::arg("section") = std::vector<double>{sec.youngs_modulus, sec.shear_modulus, sec.density, sec.area,
                                                         sec.second_moment_y, sec.second_moment_z, sec.polar_moment,
                                                         sec.shear_coefficient_y, sec.shear_coefficient_z}));
            k += std::size_t(shaft->nodes.size()) * std::size_t(shaft->dofs_per_node()) - 1;
            continue;
        }
        const DofSpec& d = all[k];
        // A linkage's coupler DOFs (<name>.x, .y, .angle, added together): one entry naming the linkage.
        const CouplerLinkage* linkage = nullptr;
        for (const CouplerLinkage& l : b.linkages)
            if (d.name == l.name + ".x") linkage = &l;
        if (linkage) {
            dofs.append(py::dict(py::arg("linkage") = linkage->name));
            k += 2;
            continue;
        }
        dofs.append(py::dict(py::arg("name") = d.name, py::arg("mass") = d.mass,
                             py::arg("direction") = Eigen::Vector3d(d.direction)));
    }
    for (const PointMassSpec& pm : b.structure.masses()) masses.append(py::make_tuple(pm.dof, pm.mass));
    for (const SpringSpec& s : b.structure.springs())
        springs.append(py::dict(py::arg("name") = s.name, py::arg("a") = s.a, py::arg("b") = s.b,
                                py::arg("stiffness") = s.stiffness, py::arg("damping") = s.damping,
                                py::arg("preload") = s.preload));
    for (const LoadSpec& l : b.structure.loads())
        loads.append(py::dict(py::arg("dof") = l.dof, py::arg("force") = l.force));
    for (const ContactPairSpec& c : b.contacts)
        contacts.append(py::dict(
            py::arg("name") = c.name, py::arg("program") = c.program,
            py::arg("follower") = follower_to_python(c.follower), py::arg("stiffness") = c.law.stiffness,
            py::arg("exponent") = c.law.exponent, py::arg("damping_factor") = c.law.damping_factor,
            py::arg("phase") = c.phase, py::arg("cam_x") = c.cam_x, py::arg("cam_y") = c.cam_y,
            py::arg("follower_dof") = c.follower_dof, py::arg("lateral") = c.lateral,
            py::arg("eccentricity") = c.eccentricity, py::arg("cam_twist") = c.cam_twist,
            py::arg("paper_backlash") = py::make_tuple(c.paper_backlash.backlash, c.paper_backlash.switch_width,
                                                       c.paper_backlash.guide_dof, c.paper_backlash.guide_stiffness),
            py::arg("groove") = c.groove ? py::cast(*c.groove) : py::none(),
            py::arg("follower_ratio") = c.follower_ratio, py::arg("follower_offset") = c.follower_offset,
            py::arg("frame_angle") = c.frame_angle));
    py::list clearances;
    for (const ClearanceSpec& c : b.clearances)
        clearances.append(py::dict(py::arg("name") = c.name, py::arg("gap") = c.gap, py::arg("clearance") = c.clearance,
                                   py::arg("stiffness") = c.wall.stiffness, py::arg("exponent") = c.wall.exponent,
                                   py::arg("damping_factor") = c.wall.damping_factor, py::arg("friction") = c.friction,
                                   py::arg("sliding_dof") = c.sliding_dof, py::arg("slip_velocity") = c.slip_velocity));
    return py::dict(py::arg("masses") = masses, py::arg("clearances") = clearances, py::arg("dofs") = dofs,
                    py::arg("springs") = springs, py::arg("loads") = loads,
                    py::arg("gravity") = Eigen::Vector3d(b.structure.gravity()),
                    py::arg("rayleigh_alpha") = b.structure.rayleigh_alpha(),
                    py::arg("rayleigh_beta") = b.structure.rayleigh_beta(),
                    py::arg("modal_ratios") = b.structure.modal_ratios(), py::arg("contacts") = contacts,
                    py::arg("camshaft_speed") = b.camshaft_speed,
                    py::arg("speed_program") = b.speed_program ? py::cast(*b.speed_program) : py::none(),
                    py::arg("linkages") = b.linkages);
}

MechanismBuilder builder_from(const py::dict& t) {
    MechanismBuilder b;
    for (const auto& item : t["dofs"].cast<py::list>()) {
        const auto d = item.cast<py::dict>();
        if (d.contains("shaft")) {
            const std::vector<double> v = d["section"].cast<std::vector<double>>();
            if (v.size() != 9) detail::fail("shaft section: 9 values expected");
            b.add_shaft({d["shaft"].cast<std::string>(),
                         BeamSection{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]}, d["length"].cast<double>(),
                         d["max_element_length"].cast<double>(), d["stations"].cast<std::vector<double>>(),
                         d["axial"].cast<bool>(), d.contains("damping") ? d["damping"].cast<double>() : 0.0});
            continue;
        }
        if (d.contains("linkage")) {
            const std::string name = d["linkage"].cast<std::string>();
            for (const CouplerLinkage& l : t["linkages"].cast<std::vector<CouplerLinkage>>())
                if (l.name == name) b.add_linkage(l);
            continue;
        }
        b.add_dof(d["name"].cast<std::string>(), d["mass"].cast<double>(), d["direction"].cast<Eigen::Vector3d>());
    }
    if (t.contains("masses"))
        for (const auto& item : t["masses"].cast<py::list>()) {
            const auto m = item.cast<py::tuple>();
            b.add_mass(m[0].cast<std::string>(), m[1].cast<double>());
        }
    for (const auto& item : t["springs"].cast<py::list>()) {
        const auto s = item.cast<py::dict>();
        b.add_spring(s["name"].cast<std::string>(), s["a"].cast<std::string>(), s["b"].cast<std::string>(),
                     s["stiffness"].cast<double>(), s["damping"].cast<double>(), s["preload"].cast<double>());
    }
    for (const auto& item : t["loads"].cast<py::list>()) {
        const auto l = item.cast<py::dict>();
        b.add_load(l["dof"].cast<std::string>(), l["force"].cast<double>());
    }
    b.set_gravity(t["gravity"].cast<Eigen::Vector3d>());
    b.set_rayleigh_damping(t["rayleigh_alpha"].cast<double>(), t["rayleigh_beta"].cast<double>());
    b.set_modal_damping(t["modal_ratios"].cast<std::vector<double>>());
    for (const auto& item : t["contacts"].cast<py::list>()) {
        const auto c = item.cast<py::dict>();
        ContactPairSpec spec{c["name"].cast<std::string>(),
                             c["program"].cast<MotionProgram>(),
                             follower_from(c["follower"]),
                             HertzContact{c["stiffness"].cast<double>(), c["exponent"].cast<double>(),
                                          c["damping_factor"].cast<double>()},
                             c["phase"].cast<double>(),
                             c["cam_x"].cast<std::string>(),
                             c["cam_y"].cast<std::string>(),
                             c["follower_dof"].cast<std::string>(),
                             c["lateral"].cast<std::string>(),
                             c.contains("eccentricity") ? c["eccentricity"].cast<CamEccentricity>() : CamEccentricity{},
                             c.contains("cam_twist") ? c["cam_twist"].cast<std::string>() : std::string(ground_name)};
        if (c.contains("paper_backlash")) {
            const auto pb = c["paper_backlash"].cast<py::tuple>();
            if (pb.size() != 4)
                detail::fail(
                    "contact paper_backlash: 4 values expected (backlash, switch_width, guide_dof, guide_stiffness)");
            spec.paper_backlash = {pb[0].cast<double>(), pb[1].cast<double>(), pb[2].cast<std::string>(),
                                   pb[3].cast<double>()};
        }
        if (c.contains("groove") && !c["groove"].is_none()) spec.groove = c["groove"].cast<Groove>();
        if (c.contains("follower_ratio")) spec.follower_ratio = c["follower_ratio"].cast<double>();
        if (c.contains("follower_offset")) spec.follower_offset = c["follower_offset"].cast<double>();
        if (c.contains("frame_angle")) spec.frame_angle = c["frame_angle"].cast<double>();
        b.add_contact(spec);
    }
    if (t.contains("clearances"))
        for (const auto& item : t["clearances"].cast<py::list>()) {
            const auto c = item.cast<py::dict>();
            b.add_clearance({c["name"].cast<std::string>(),
                             c["gap"].cast<std::vector<std::pair<std::string, double>>>(),
                             c["clearance"].cast<double>(),
                             HertzContact{c["stiffness"].cast<double>(), c["exponent"].cast<double>(),
                                          c["damping_factor"].cast<double>()},
                             c["friction"].cast<double>(), c["sliding_dof"].cast<std::string>(),
                             c["slip_velocity"].cast<double>()});
        }
    if (t.contains("speed_program") && !t["speed_program"].is_none())
        b.speed_program = t["speed_program"].cast<SpeedProgram>();
    b.camshaft_speed = t["camshaft_speed"].cast<double>();
    return b;
}

py::dict modal(const AnyMechanism& m, double theta) {
    return m.visit([&](const auto& mech) {
        const MechanismModes r = lowest_modes(mech, theta);
        py::dict d;
        d["frequencies_hz"] = r.frequencies_hz;
        d["mode_shapes"] = r.shapes;
        d["tangent_stiffness"] = r.tangent_stiffness;
        return d;
    });
}

}  // namespace

void bind_mechanism(py::module_& m) {
    py::enum_<ArmTurn>(m, "ArmTurn", "Sense in which an oscillating follower's arm turns to lift.")
        .value("counter_clockwise", ArmTurn::counter_clockwise)
        .value("clockwise", ArmTurn::clockwise);

    bind_followers(m, static_cast<const Follower*>(nullptr));

    py::class_<CamEccentricity>(
        m, "CamEccentricity",
        "An eccentric cam: its geometric centre at `radius` (m) from the bearing axis, in the direction `phase`\n"
        "(rad) of the cam frame, so at epsilon (cos(theta + phase), sin(theta + phase)) in the ground frame.\n"
        "formulation: 'exact' (the displaced profile's contact geometry; physical), or the paper's literal\n"
        "force K_h epsilon sin(theta + phase) on the camshaft, the roller or both ('paper_force_camshaft',\n"
        "'paper_force_roller', 'paper_force_both'; not physically derived, kept to reproduce the paper).\n"
        "unbalance_mass (kg): a rotating unbalance m epsilon omega^2 on the cam centre's DOFs.")
        .def(py::init([](double radius, double phase, const std::string& formulation, double unbalance_mass) {
                 CamEccentricity e{radius, phase, eccentricity_formulation_from(formulation), unbalance_mass};
                 e.validate("CamEccentricity");
                 return e;
             }),
             py::arg("radius"), py::arg("phase") = 0.0, py::arg("formulation") = "exact",
             py::arg("unbalance_mass") = 0.0)
        .def_readonly("radius", &CamEccentricity::radius, "m")
        .def_readonly("phase", &CamEccentricity::phase, "rad")
        .def_property_readonly(
            "formulation",
            [](const CamEccentricity& e) { return std::string(eccentricity_formulation_name(e.formulation)); })
        .def_readonly("unbalance_mass", &CamEccentricity::unbalance_mass, "kg")
        .def(py::pickle(
            [](const CamEccentricity& e) {
                return py::make_tuple(e.radius, e.phase, std::string(eccentricity_formulation_name(e.formulation)),
                                      e.unbalance_mass);
            },
            [](const py::tuple& t) {
                return CamEccentricity{t[0].cast<double>(), t[1].cast<double>(),
                                       eccentricity_formulation_from(t[2].cast<std::string>()), t[3].cast<double>()};
            }))
        .def("__repr__", [](const CamEccentricity& e) {
            return detail::concat("CamEccentricity(radius=", e.radius, ", phase=", e.phase, ", formulation='",
                                  eccentricity_formulation_name(e.formulation), "', unbalance_mass=", e.unbalance_mass,
                                  ")");
        });

    py::class_<Groove>(
        m, "Groove",
        "A face groove (form closure) for a roller contact: the roller runs between the cam's inner flank (the\n"
        "contact's own surface) and an outer flank, the pitch curve's parallel at roller radius + clearance.\n"
        "clearance (m): groove width minus the roller's diameter, in (0, roller radius). The outer flank's Hertz\n"
        "law F = stiffness delta^exponent (1 + damping_factor delta'): the contact's own when stiffness is None\n"
        "(the outer flank is concave towards the roller: for the same material its stiffness is higher).")
        .def(py::init(
                 [](double clearance, const std::optional<double>& stiffness, double exponent, double damping_factor) {
                     Groove g{clearance, std::nullopt};
                     if (stiffness) g.law = HertzContact{*stiffness, exponent, damping_factor};
                     else if (exponent != 1.0 || damping_factor != 0.0)
                         detail::fail(
                             "Groove: exponent and damping_factor belong to the outer flank's own law; give its "
                             "stiffness too (or none of them to use the contact's law)");
                     // The clearance against the roller is checked where the contact is built.
                     g.validate("Groove:", std::numeric_limits<double>::infinity());
                     return g;
                 }),
             py::arg("clearance"), py::kw_only(), py::arg("stiffness") = py::none(), py::arg("exponent") = 1.0,
             py::arg("damping_factor") = 0.0)
        .def_readonly("clearance", &Groove::clearance, "m")
        .def_property_readonly(
            "stiffness", [](const Groove& g) { return g.law ? py::cast(g.law->stiffness) : py::none(); },
            "the outer flank's N/m^n, or None (the contact's law)")
        .def_property_readonly("exponent", [](const Groove& g) { return g.law ? g.law->exponent : 1.0; })
        .def_property_readonly("damping_factor", [](const Groove& g) { return g.law ? g.law->damping_factor : 0.0; })
        .def(py::pickle(
            [](const Groove& g) {
                return py::make_tuple(g.clearance, g.law ? py::cast(g.law->stiffness) : py::none(),
                                      g.law ? g.law->exponent : 1.0, g.law ? g.law->damping_factor : 0.0);
            },
            [](const py::tuple& t) {
                Groove g{t[0].cast<double>(), std::nullopt};
                if (!t[1].is_none())
                    g.law = HertzContact{t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>()};
                return g;
            }))
        .def("__repr__", [](const Groove& g) {
            if (!g.law) return detail::concat("Groove(clearance=", g.clearance, ")");
            return detail::concat("Groove(clearance=", g.clearance, ", stiffness=", g.law->stiffness,
                                  ", exponent=", g.law->exponent, ", damping_factor=", g.law->damping_factor, ")");
        });

    py::class_<MechanismBuilder> builder(
        m, "MechanismBuilder",
        "Describe a cam mechanism: DOFs with masses, springs and dampers between DOFs or to 'ground', loads,\n"
        "gravity, global damping, and cam-follower contact pairs. build() makes the immutable Mechanism.\n"
        "SI units: kg (kg m^2 for a rotation), N/m, N s/m, N; angles in rad.");
    builder.def(py::init<>())
        .def("add_dof", &MechanismBuilder::add_dof, py::arg("name"), py::arg("mass"),
             py::arg("direction") = Eigen::Vector3d::Zero(),
             "A DOF: mass (kg, or kg m^2 for a rotation) and, for a translation, its unit direction in space (for "
             "gravity).")
        .def(
            "add_spring", &MechanismBuilder::add_spring, py::arg("name"), py::arg("a"), py::arg("b") = ground_name,
            py::kw_only(), py::arg("stiffness"), py::arg("damping") = 0.0, py::arg("preload") = 0.0,
            "Spring-damper between DOFs a and b (or 'ground'); force on a: -(preload + k (q_a - q_b) + c (v_a - v_b)).")
        .def("add_damper", &MechanismBuilder::add_damper, py::arg("name"), py::arg("a"), py::arg("b") = ground_name,
             py::kw_only(), py::arg("damping"))
        .def("add_load", &MechanismBuilder::add_load, py::arg("dof"), py::arg("force"), "Constant load along +q (N).")
        .def("set_gravity", &MechanismBuilder::set_gravity, py::arg("gravity"), "Gravity vector (m/s^2).")
        .def("set_rayleigh_damping", &MechanismBuilder::set_rayleigh_damping, py::arg("alpha"), py::arg("beta"),
             "C += alpha M + beta K.")
        .def("set_modal_damping", &MechanismBuilder::set_modal_damping, py::arg("ratios"),
             "C += modal damping with these ratios (one for all modes, or one per mode, ascending), over the modes "
             "at the initial equilibrium with the contacts linearized.")
        .def(
            "add_contact",
            [](MechanismBuilder& b, const std::string& name, const MotionProgram& program, const py::object& follower,
               const std::string& follower_dof, double stiffness, double exponent, double damping_factor, double phase,
               const std::string& cam_x, const std::string& cam_y, const std::string& lateral,
               const std::optional<CamEccentricity>& eccentricity, const std::string& cam_twist,
               const std::optional<Groove>& groove, double follower_ratio, double follower_offset, double frame_angle) {
                ContactPairSpec spec{name,
                                     program,
                                     follower_from(follower),
                                     HertzContact{stiffness, exponent, damping_factor},
                                     phase,
                                     cam_x,
                                     cam_y,
                                     follower_dof,
                                     lateral,
                                     eccentricity.value_or(CamEccentricity{}),
                                     cam_twist};
                spec.groove = groove;
                spec.follower_ratio = follower_ratio, spec.follower_offset = follower_offset;
                spec.frame_angle = frame_angle;
                b.add_contact(spec);
            },
            py::arg("name"), py::arg("program"), py::arg("follower"), py::kw_only(), py::arg("follower_dof"),
            py::arg("stiffness"), py::arg("exponent") = 1.0, py::arg("damping_factor") = 0.0, py::arg("phase") = 0.0,
            py::arg("cam_x") = ground_name, py::arg("cam_y") = ground_name, py::arg("lateral") = ground_name,
            py::arg("eccentricity") = py::none(), py::arg("cam_twist") = ground_name, py::arg("groove") = py::none(),
            py::arg("follower_ratio") = 1.0, py::arg("follower_offset") = 0.0, py::arg("frame_angle") = 0.0,
            "A cam-follower contact pair: the cam's lift program (m, or rad for an oscillating follower), the "
            "follower\n"
            "type, the DOF of the follower's coordinate, a Hertz law F = k delta^n (1 + chi delta'), the cam's\n"
            "phase on the shaft (rad), the cam centre's DOFs, a translating follower's lateral DOF, an optional\n"
            "CamEccentricity, and the camshaft's twist DOF at the cam (rad; the cam angle is then omega t + phase +\n"
            "twist, a state, and the contact's moment loads the twist: channel <name>.cam_torque), and an optional\n"
            "Groove for a roller held between two flanks (channels <name>.penetration_rate, .outer_force,\n"
            ".outer_penetration, .outer_in_contact; event <name>.outer_contact). follower_ratio, follower_offset:\n"
            "the pair's follower coordinate is follower_offset + follower_ratio * q_follower (a second roller on\n"
            "one follower); frame_angle (rad): the pair's frame turned from the ground frame about the cam axis.")
        .def(
            "add_conjugate_cams",
            [](MechanismBuilder& b, const std::string& name, const MotionProgram& program, const py::object& follower,
               const py::object& return_follower, const std::string& follower_dof, double stiffness, double exponent,
               double damping_factor, double backlash, double phase, const std::optional<MotionProgram>& return_program,
               std::optional<double> return_stiffness, std::optional<double> return_exponent,
               std::optional<double> return_damping_factor, const std::string& cam_x, const std::string& cam_y,
               const std::string& lateral, const std::string& cam_twist) {
                const HertzContact law{stiffness, exponent, damping_factor};
                ConjugateCams c{name,
                                program,
                                follower_from(follower),
                                follower_from(return_follower),
                                return_program,
                                law,
                                std::nullopt,
                                phase,
                                backlash,
                                cam_x,
                                cam_y,
                                follower_dof,
                                lateral,
                                cam_twist};
                if (return_stiffness || return_exponent || return_damping_factor)
                    c.return_law =
                        HertzContact{return_stiffness.value_or(stiffness), return_exponent.value_or(exponent),
                                     return_damping_factor.value_or(damping_factor)};
                b.add_conjugate_cams(c);
                // A bell crank's angle from the lift arm to the return arm: what its drawing needs.
                return is_translating(c.follower) ? py::object(py::none()) : py::object(py::float_(c.arm_angle()));
            },
            py::arg("name"), py::arg("program"), py::arg("follower"), py::arg("return_follower"), py::kw_only(),
            py::arg("follower_dof"), py::arg("stiffness"), py::arg("exponent") = 1.0, py::arg("damping_factor") = 0.0,
            py::arg("backlash") = 0.0, py::arg("phase") = 0.0, py::arg("return_program") = py::none(),
            py::arg("return_stiffness") = py::none(), py::arg("return_exponent") = py::none(),
            py::arg("return_damping_factor") = py::none(), py::arg("cam_x") = ground_name,
            py::arg("cam_y") = ground_name, py::arg("lateral") = ground_name, py::arg("cam_twist") = ground_name,
            "Conjugate cams: two cams on one shaft holding one follower both ways, the contacts '<name>.lift'\n"
            "(program, follower) and '<name>.return' (return_follower on the cam of return_program, by default the\n"
            "complement H - h with H the program's highest lift). A translating pair's return roller sits across\n"
            "the cam centre (its frame turned by pi, its offset measured in that frame); an oscillating pair's\n"
            "arms share the pivot and lift in opposite senses. backlash (m, or rad for an arm): the follower's play\n"
            "between the cams (> 0) or the interference that preloads them (< 0). return_*: the return contact's\n"
            "law where it differs. Returns an oscillating pair's bell-crank angle (rad, counter-clockwise from the\n"
            "lift arm to the return arm, both rollers on their cams), None for a translating pair.")
        .def(
            "add_shaft",
            [](MechanismBuilder& b, const std::string& name, double length, double outer_diameter,
               double inner_diameter, const std::vector<double>& stations, double max_element_length,
               double youngs_modulus, double poisson_ratio, double density, bool axial, double damping) {
                b.add_shaft(
                    {name,
                     BeamSection::hollow_circle(outer_diameter, inner_diameter, youngs_modulus, poisson_ratio, density),
                     length, max_element_length, stations, axial, damping});
            },
            py::arg("name"), py::kw_only(), py::arg("length"), py::arg("outer_diameter"),
            py::arg("inner_diameter") = 0.0, py::arg("stations") = std::vector<double>{},
            py::arg("max_element_length") = 0.0, py::arg("youngs_modulus") = 210e9, py::arg("poisson_ratio") = 0.3,
            py::arg("density") = 7850.0, py::arg("axial") = false, py::arg("damping") = 0.0,
            "A flexible shaft along x from 0 to `length` (m): Timoshenko beam elements (bending in two planes with\n"
            "shear and rotary inertia, torsion; axial if asked) of a solid or hollow circular steel section (SI\n"
            "units). Every station (m) where a cam, bearing, drive or mass will sit must be listed; no element is\n"
            "longer than max_element_length (0: one element between stations). Node DOFs are named\n"
            "'<name>.<node>.<uy|uz|rx|ry|rz>' (shaft_dof()); the twist rx is relative to the rigid rotation.\n"
            "damping (s): material damping C = damping K of the shaft's elements (mode ratio damping omega / 2).")
        .def(
            "shaft_dof",
            [](const MechanismBuilder& b, const std::string& shaft, double at, const std::string& dof) {
                static const char* names[] = {"ux", "uy", "uz", "rx", "ry", "rz"};
                for (int d = 0; d < 6; ++d)
                    if (dof == names[d]) return b.structure.shaft_dof_at(shaft, at, d);
                detail::fail("dof must be one of 'ux', 'uy', 'uz', 'rx', 'ry', 'rz', got '", dof, "'");
            },
            py::arg("shaft"), py::arg("at"), py::arg("dof"), "The DOF name of a shaft's node at station `at` (m).")
        .def("add_bearing", &MechanismBuilder::add_bearing, py::arg("name"), py::arg("shaft"), py::arg("at"),
             py::kw_only(), py::arg("stiffness"), py::arg("damping") = 0.0,
             "A radial bearing at station `at` (m): spring-dampers (N/m, N s/m) from u_y and u_z to ground.")
        .def("add_drive", &MechanismBuilder::add_drive, py::arg("name"), py::arg("shaft"), py::arg("at") = 0.0,
             py::kw_only(), py::arg("stiffness"), py::arg("damping") = 0.0,
             "The drive as an imposed speed through a compliance: a torsional spring-damper (N m/rad, N m s/rad)\n"
             "from the twist at station `at` to the rigid rotation omega t.")
        .def("add_motor", &MechanismBuilder::add_motor, py::arg("name"), py::arg("shaft"), py::arg("at") = 0.0,
             py::kw_only(), py::arg("inertia"), py::arg("position_gain"), py::arg("velocity_gain") = 0.0,
             py::arg("torque") = 0.0,
             "The drive as a speed-controlled motor with a flywheel at `at`: inertia (kg m^2) on the twist, the\n"
             "controller's position gain (N m/rad, > 0) and velocity gain (N m s/rad) to the nominal rotation, and\n"
             "a constant forward torque (N m, e.g. the cams' mean torque as feed-forward).")
        .def(
            "mount_cam",
            [](MechanismBuilder& b, const std::string& name, const MotionProgram& program, const py::object& follower,
               const std::string& follower_dof, const std::string& shaft, double at, double stiffness, double exponent,
               double damping_factor, double phase, double width, double cam_mass, double cam_inertia,
               const std::string& lateral) {
                b.mount_cam({name, program, follower_from(follower), HertzContact{stiffness, exponent, damping_factor},
                             phase, ground_name, ground_name, follower_dof, lateral, CamEccentricity{}, ground_name},
                            shaft, at, width, cam_mass, cam_inertia);
            },
            py::arg("name"), py::arg("program"), py::arg("follower"), py::kw_only(), py::arg("follower_dof"),
            py::arg("shaft"), py::arg("at"), py::arg("stiffness"), py::arg("exponent") = 1.0,
            py::arg("damping_factor") = 0.0, py::arg("phase") = 0.0, py::arg("width") = 0.0, py::arg("cam_mass") = 0.0,
            py::arg("cam_inertia") = 0.0, py::arg("lateral") = ground_name,
            "A contact pair whose cam sits on a shaft at station `at` (m): the cam centre is the node's (u_y, u_z), "
            "its\n"
            "angle omega t + phase + the node's twist. Its contact frame has x along the global y and the follower's\n"
            "axis along the global z (a barrel cam's: x along the global y, its follower's axis along the shaft, so\n"
            "the cam centre is the node's (u_y, u_x) and the shaft needs axial=True). width (m) is checked against\n"
            "the other cams; cam_mass (kg) and cam_inertia (kg m^2) are added to the node.")
        .def("add_spring_chain", &MechanismBuilder::add_spring_chain, py::arg("name"), py::arg("a"),
             py::arg("b") = ground_name, py::kw_only(), py::arg("stiffness"), py::arg("mass"), py::arg("elements") = 6,
             py::arg("damping") = 0.0, py::arg("preload") = 0.0, py::arg("direction") = Eigen::Vector3d::Zero(),
             "A spring with its own mass (a valve spring that surges): `elements` equal springs in series with\n"
             "interior masses '<name>.1', ...; its surge frequencies tend to (j / 2) sqrt(stiffness / mass) with both\n"
             "ends held. stiffness, damping and preload are the whole spring's.")
        .def("add_mass", &MechanismBuilder::add_mass, py::arg("dof"), py::arg("mass"),
             "A lumped mass (kg) or inertia (kg m^2) added to a DOF (e.g. a flywheel on a shaft's twist).")
        .def(
            "add_clearance",
            [](MechanismBuilder& b, const std::string& name, const std::vector<std::pair<std::string, double>>& gap,
               double clearance, double stiffness, double exponent, double damping_factor, double friction,
               const std::string& sliding_dof, double slip_velocity) {
                b.add_clearance({name, gap, clearance, HertzContact{stiffness, exponent, damping_factor}, friction,
                                 sliding_dof, slip_velocity});
            },
            py::arg("name"), py::arg("gap"), py::kw_only(), py::arg("clearance"), py::arg("stiffness"),
            py::arg("exponent") = 1.0, py::arg("damping_factor") = 0.0, py::arg("friction") = 0.0,
            py::arg("sliding_dof") = "", py::arg("slip_velocity") = 1e-3,
            "A radial clearance: the gap coordinate u = sum c_j q_j (gap: [(dof, c_j), ...], m) is free for |u| <= "
            "clearance\n"
            "(m) and meets a wall law F = k delta^n (1 + chi delta') beyond; with friction > 0, regularized Coulomb\n"
            "friction mu F tanh(v / slip_velocity) on sliding_dof. Channels <name>.force, .side, .gap, .friction.")
        .def(
            "add_guide",
            [](MechanismBuilder& b, const std::string& name, const std::string& lateral_dof, double clearance,
               double length, const std::vector<double>& bushings, const std::string& tilt_dof, double tilt_reference,
               double stiffness, double exponent, double damping_factor, double friction,
               const std::string& sliding_dof, double slip_velocity) {
                b.add_guide({name, lateral_dof, tilt_dof, sliding_dof, length, bushings, tilt_reference, clearance,
                             HertzContact{stiffness, exponent, damping_factor}, friction, slip_velocity});
            },
            py::arg("name"), py::arg("lateral_dof"), py::kw_only(), py::arg("clearance"), py::arg("length"),
            py::arg("bushings"), py::arg("tilt_dof") = "", py::arg("tilt_reference") = 0.0, py::arg("stiffness"),
            py::arg("exponent") = 1.0, py::arg("damping_factor") = 0.0, py::arg("friction") = 0.0,
            py::arg("sliding_dof") = "", py::arg("slip_velocity") = 1e-3,
            "A rod in a guide of `length` (m) with one or two bushings at axial positions (m, in [0, length]); two\n"
            "bushings need the rod's tilt DOF (rad, about tilt_reference). One clearance per bushing\n"
            "(<name>, or <name>.bushing1/.bushing2).")
        .def("add_linkage", &MechanismBuilder::add_linkage, py::arg("linkage"),
             "Add a CouplerLinkage: its coupler's DOFs <name>.x, <name>.y, <name>.angle and the pin joints\n"
             "<name>.input, <name>.output (channels .force, .stretch), assembled at q = 0.")
        .def_property_readonly(
            "linkages", [](const MechanismBuilder& b) { return b.linkages; }, "The linkages added, in order.")
        .def_property(
            "camshaft_speed_rpm", &MechanismBuilder::camshaft_speed_rpm, &MechanismBuilder::set_camshaft_speed_rpm,
            "The camshaft speed, rpm (with a speed program its nominal speed: setting it scales the program).")
        .def_property(
            "speed_program", [](const MechanismBuilder& b) { return b.speed_program; },
            [](MechanismBuilder& b, const std::optional<SpeedProgram>& p) {
                if (p) b.set_speed_program(*p);
                else b.speed_program.reset();
            },
            "A variable camshaft speed (SpeedProgram), or None: constant camshaft_speed_rpm. Setting one makes its\n"
            "nominal speed the camshaft speed.")
        .def_property_readonly("dof_names",
                               [](const MechanismBuilder& b) {
                                   std::vector<std::string> n;
                                   for (const DofSpec& d : b.structure.dofs()) n.push_back(d.name);
                                   return n;
                               })
        .def("build", &AnyMechanism::build, "Validate and assemble the immutable Mechanism.")
        .def(py::pickle(&builder_state, &builder_from));
    // The description read back, one list per kind (copies: change the builder through its add_ methods).
    const std::pair<const char*, const char*> parts[] = {
        {"dofs",
         "DOFs in order, as dicts (name, mass, direction); a shaft's DOFs as one dict describing the shaft, a "
         "linkage's coupler DOFs as one dict naming the linkage."},
        {"masses", "Point masses added to DOFs, as (dof, mass) tuples (kg)."},
        {"springs", "Springs and dampers, as dicts (name, a, b, stiffness, damping, preload)."},
        {"loads", "Constant loads, as dicts (dof, force)."},
        {"contacts",
         "Cam-follower contacts, as dicts with add_contact's parameters (name, program, follower, "
         "stiffness, exponent, damping_factor, phase, cam_x, cam_y, follower_dof, lateral, eccentricity, "
         "cam_twist, groove) and paper_backlash (backlash, switch_width, guide_dof, guide_stiffness)."},
        {"clearances", "Clearances, as dicts with add_clearance's parameters."},
    };
    for (const auto& [key, doc] : parts) {
        const std::string k = key;
        builder.def_property_readonly(
            key,
            [k](const MechanismBuilder& b) {
                const py::dict state = builder_state(b);
                return py::object(state[k.c_str()]);
            },
            doc);
    }

    py::class_<AnyMechanism>(m, "Mechanism",
                             "An immutable cam mechanism (build one with MechanismBuilder, or camfollower.presets).\n"
                             "simulate(mechanism, ...) integrates it; channels: theta and per contact <name>.force,\n"
                             ".penetration, .stiffness, .pressure_angle, .cam_angle, .in_contact.")
        .def(py::init(&AnyMechanism::build), py::arg("builder"))
        .def_property_readonly("size",
                               [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.size(); }); })
        .def_property_readonly(
            "dof_names", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.dof_names(); }); })
        .def_property_readonly("contact_names",
                               [](const AnyMechanism& a) {
                                   return a.visit([](const auto& x) {
                                       std::vector<std::string> n;
                                       for (const ContactPair& c : x.contacts()) n.push_back(c.name());
                                       return n;
                                   });
                               })
        .def_property_readonly("clearance_names",
                               [](const AnyMechanism& a) {
                                   return a.visit([](const auto& x) {
                                       std::vector<std::string> n;
                                       for (const Clearance& c : x.clearances()) n.push_back(c.name());
                                       return n;
                                   });
                               })
        .def_property_readonly(
            "follower_dofs",
            [](const AnyMechanism& a) {
                return a.visit([](const auto& x) {
                    std::vector<std::string> n;
                    for (const ContactPair& c : x.contacts()) n.push_back(c.spec().follower_dof);
                    return n;
                });
            },
            "the follower DOF of each contact")
        .def_property_readonly(
            "warnings", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.warnings(); }); },
            "what the formulation warns about (also issued as UserWarning when built)")
        .def_property_readonly(
            "initial_velocity",
            [](const AnyMechanism& a) {
                return a.visit([](const auto& x) { return Eigen::VectorXd(x.initial_velocity()); });
            },
            "quasi-static velocity at t = 0 (the rate of the static equilibrium as the cam turns)")
        .def_property_readonly(
            "mass",
            [](const AnyMechanism& a) { return a.visit([](const auto& x) { return Eigen::MatrixXd(x.mass()); }); })
        .def_property_readonly(
            "damping",
            [](const AnyMechanism& a) { return a.visit([](const auto& x) { return Eigen::MatrixXd(x.damping()); }); })
        .def_property_readonly(
            "stiffness",
            [](const AnyMechanism& a) { return a.visit([](const auto& x) { return Eigen::MatrixXd(x.stiffness()); }); })
        .def_property_readonly(
            "initial_state",
            [](const AnyMechanism& a) {
                return a.visit([](const auto& x) { return Eigen::VectorXd(x.initial_displacement()); });
            },
            "static equilibrium at t = 0 (m or rad per DOF)")
        .def_property_readonly(
            "omega", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.omega(); }); },
            "camshaft speed, rad/s (with a speed program its nominal speed)")
        .def_property_readonly(
            "period", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.period(); }); },
            "one camshaft revolution at omega, s")
        .def_property_readonly(
            "speed_program", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.drive(); }); },
            "The camshaft's rotation (a SpeedProgram; constant at omega without a speed program).")
        .def_property_readonly(
            "periodic", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.periodic(); }); },
            "The motion repeats every period (no speed ramps): settling and the periodic steady state apply.")
        .def_property_readonly("camshaft_speed_rpm",
                               [](const AnyMechanism& a) {
                                   return a.visit([](const auto& x) { return x.description().camshaft_speed_rpm(); });
                               })
        .def(
            "static_equilibrium",
            [](const AnyMechanism& a, double theta) {
                return a.visit([&](const auto& x) { return Eigen::VectorXd(x.static_equilibrium(theta)); });
            },
            py::arg("theta"), "Quasi-static equilibrium at camshaft angle theta (rad).")
        .def(
            "quasi_static_path",
            [](const AnyMechanism& a, const std::string& dof, const std::vector<double>& theta, int angles) {
                return a.visit([&](const auto& x) {
                    const int i = x.dof_index(dof);
                    py::gil_scoped_release release;
                    const std::vector<double> path = synthesis::quasi_static_path(x, i, theta, angles);
                    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(path.data(), Eigen::Index(path.size())));
                });
            },
            py::arg("dof"), py::arg("theta"), py::arg("angles") = synthesis::quasi_static_angles,
            "The DOF's static equilibrium at the shaft angles theta (rad, in [0, 2 pi]): solved at `angles`\n"
            "equally spaced angles (default every 0.5 deg) and interpolated periodically, or with angles = 0 at\n"
            "every theta (synthesis/lift_samples.hpp). RuntimeError where the mechanism has no static equilibrium.")
        .def(
            "step_limit",
            [](const AnyMechanism& a, double beta) {
                detail::require_in_range(beta, 0.0, 0.25, "beta");
                return a.visit([&](const auto& x) {
                    SolverSettings s;
                    s.method = Method::newmark, s.gamma = 0.5, s.beta = beta;
                    const NewmarkParameters p = newmark_parameters(s);
                    const auto q = x.static_equilibrium(0.0);
                    const StepLimit limit = step_limit(x, state_at(x, 0.0, q, decltype(q)::Zero(q.size())), p);
                    py::dict d;
                    d["step"] = limit.step;
                    d["frequency_hz"] = limit.omega / (2.0 * pi);
                    d["damping_ratio"] = limit.damping_ratio;
                    return d;
                });
            },
            py::arg("beta"),
            "Largest stable time step (s) of Newmark with gamma = 1/2 and this beta in [0, 1/4] at the\n"
            "quasi-static equilibrium at t = 0 (contacts linearized), with the solver's 10 % margin, and the mode\n"
            "that sets it (frequency_hz, damping_ratio); +inf at beta = 1/4. Below 1/4 the velocity is processed\n"
            "to fourth order, and damping lowers the limit (docs/solvers.md). A fixed step above it is refused.")
        .def("modal_analysis", &modal, py::arg("theta") = 0.0,
             "Undamped natural frequencies (Hz, ascending), mass-normalized mode shapes and the tangent stiffness at\n"
             "the quasi-static equilibrium at camshaft angle theta (rad), contacts linearized: every mode, as\n"
             "lowest_modes(theta) (the one modal analysis).")
        .def(
            "lowest_modes",
            [](const AnyMechanism& a, double theta, int count) {
                return a.visit([&](const auto& x) {
                    const MechanismModes r = lowest_modes(x, theta, count);
                    return py::make_tuple(r.frequencies_hz, r.shapes);
                });
            },
            py::arg("theta") = 0.0, py::arg("count") = 0,
            "(frequencies in Hz ascending, mass-normalized mode shapes as columns) of the lowest `count` modes at\n"
            "camshaft angle theta (rad), contacts linearized; count = 0: all (a dense solve). A few of a large\n"
            "model (above 200 DOFs, a flexible camshaft): shift-invert Lanczos on the sparse factor (Spectra).")
        .def(
            "builder", [](const AnyMechanism& a) { return a.visit([](const auto& x) { return x.description(); }); },
            "A copy of the description it was built from: change it and build() a changed mechanism.")
        .def(
            "with_camshaft_speed_rpm",
            [](const AnyMechanism& a, double rpm) {
                MechanismBuilder b = a.visit([](const auto& x) { return x.description(); });
                b.set_camshaft_speed_rpm(rpm);
                return AnyMechanism::build(b);
            },
            py::arg("rpm"), "The same mechanism at another camshaft speed (a new object).")
        .def(py::pickle(
            [](const AnyMechanism& a) { return builder_state(a.visit([](const auto& x) { return x.description(); })); },
            [](const py::dict& t) { return AnyMechanism::build(builder_from(t)); }))
        .def("__repr__", [](const AnyMechanism& a) {
            return a.visit([](const auto& x) {
                return detail::concat("Mechanism(", x.size(), " DOFs, ", x.contacts().size(), " contacts, ",
                                      x.description().camshaft_speed_rpm(), " rpm)");
            });
        });

    m.attr("realistic_damping_ratio") = presets::realistic_damping_ratio;
    m.def(
        "paper_preset",
        [](const std::optional<CamFollowerParameters>& p, const std::optional<MotionProgram>& program,
           const std::optional<CamEccentricity>& eccentricity, double guide_clearance, double guide_wall_damping_factor,
           double guide_friction, double element_damping_ratio, double paper_backlash,
           double paper_backlash_switch_width) {
            presets::PaperOptions o;
            o.eccentricity = eccentricity.value_or(CamEccentricity{});
            o.guide_clearance = guide_clearance;
            o.guide_wall_damping_factor = guide_wall_damping_factor;
            o.guide_friction = guide_friction;
            o.element_damping_ratio = element_damping_ratio;
            o.paper_backlash = paper_backlash;
            o.paper_backlash_switch_width = paper_backlash_switch_width;
            AnyMechanism a(presets::paper(p.value_or(CamFollowerParameters{}),
                                          program.value_or(MotionProgram::paper_default()), o));
            a.warn();
            return a;
        },
        py::arg("parameters") = py::none(), py::arg("program") = py::none(), py::kw_only(),
        py::arg("eccentricity") = py::none(), py::arg("guide_clearance") = 0.0,
        py::arg("guide_wall_damping_factor") = 0.0, py::arg("guide_friction") = 0.0,
        py::arg("element_damping_ratio") = 0.0, py::arg("paper_backlash") = 0.0,
        py::arg("paper_backlash_switch_width") = 0.0,
        "The paper's 7-DOF model (Tounsi et al.) built from the mechanism parts; DOFs y1..y4, x1..x3,\n"
        "contact 'cam'. parameters: a Parameters (Table 2 defaults). Options: a CamEccentricity;\n"
        "guide_clearance (m, radial) > 0 puts the rod x3 in a gap with walls of stiffness K_rb (clearance\n"
        "'guide'; wall damping factor chi in s/m, Coulomb friction on y3); element_damping_ratio in (0, 1)\n"
        "puts a damper on every element (springs, contact, guide walls) at that ratio of its own critical\n"
        "damping, in place of the paper's few dampers. paper_backlash (m) > 0: the paper's literal backlash, the\n"
        "rod's side imposed by the program (offset e +- b, K_rb anchored on the displaced rod), its switch\n"
        "ramped over paper_backlash_switch_width (rad; 0: hard).");

    m.def(
        "valve_train_preset",
        [](double engine_speed_rpm, const py::dict& parameters) {
            presets::ValveTrainParameters p;
            p.engine_speed_rpm = engine_speed_rpm;
            for (const auto& [k, v] : parameters) {
                const std::string key = py::str(k);
                if (key == "cylinders") p.cylinders = v.cast<int>();
                else if (key == "valves_per_cylinder") p.valves_per_cylinder = v.cast<int>();
                else if (key == "spring_elements") p.spring_elements = v.cast<int>();
                else if (key == "firing_order") p.firing_order = v.cast<std::vector<int>>();
                else p.ref(key) = v.cast<double>();
            }
            return AnyMechanism::build(presets::valve_train(p));
        },
        py::arg("engine_speed_rpm"), py::arg("parameters"), "Internal: camfollower.presets.valve_train() calls this.");
    m.def(
        "valve_train_parameter_units",
        [] {
            py::dict d;
            for (const auto& f : presets::ValveTrainParameters::fields()) d[py::str(f.name)] = f.unit;
            return d;
        },
        "The valve-train preset's real-valued parameters and their SI units.");

    bind_run<AnyMechanism>(m, [](const AnyMechanism& a, auto&&... args) {
        return a.visit([&](const auto& mech) { return run_system(mech, args...); });
    });
    bind_shoot<AnyMechanism>(m, [](const AnyMechanism& a, auto&&... args) {
        return a.visit([&](const auto& mech) { return shoot_system(mech, args...); });
    });

    m.def(
        "_lift_samples",
        [](const AnyMechanism& a, const std::string& contact, const std::string& output, const std::string& objective,
           const std::vector<double>& theta, const std::vector<double>& q, const std::vector<double>& acceleration,
           const std::vector<double>& force, const std::optional<MotionProgram>& dwells_of) {
            const synthesis::LiftObjective kind = synthesis::lift_objective(objective);
            const auto windows = dwells_of ? std::optional(synthesis::dwell_windows(*dwells_of)) : std::nullopt;
            return a.visit([&](const auto& x) {
                std::size_t index = x.contacts().size();
                for (std::size_t c = 0; c < x.contacts().size(); ++c)
                    if (x.contacts()[c].spec().name == contact) index = c;
                if (index == x.contacts().size()) detail::fail("contact: the mechanism has no contact '", contact, "'");
                const int dof = x.dof_index(output);
                synthesis::LiftSamples r;
                {
                    py::gil_scoped_release release;
                    r = synthesis::lift_samples(x, index, dof, kind, theta, q, acceleration, force, windows);
                }
                py::dict d;
                d["theta"] = r.theta;
                d["values"] = r.values;
                d["min_force"] = r.min_force;
                d["peak_acceleration"] = r.peak_acceleration;
                d["dwell_peak_to_peak"] = r.dwells.peak_to_peak;
                d["dwell_rms"] = r.dwells.rms;
                return d;
            });
        },
        py::arg("system"), py::arg("contact"), py::arg("output"), py::arg("objective"), py::arg("theta"), py::arg("q"),
        py::arg("acceleration"), py::arg("force"), py::arg("dwells_of") = py::none(),
        "Internal: camfollower.synthesis reduces a recorded revolution with this (synthesis/lift_samples.hpp).");

    m.def(
        "_run_many",
        [](const py::list& cases, const SolverSettings& settings, std::size_t decimation, double max_output_bytes,
           unsigned threads, const py::object& progress, double progress_interval, double settle_tolerance,
           int settle_min_revolutions, int settle_max_revolutions) {
            const SolverSettings s = as_run(settings);
            std::vector<ManyCase> jobs;
            jobs.reserve(cases.size());
            for (std::size_t i = 0; i < cases.size(); ++i) {
                const auto c = cases[i].cast<py::tuple>();
                SettleOptions settle;
                if (!c[3].is_none()) {
                    settle.enabled = true;
                    settle.period = c[3].cast<double>();
                    settle.dofs = c[4].cast<std::vector<int>>();
                    settle.tolerance = settle_tolerance;
                    settle.min_revolutions = settle_min_revolutions;
                    settle.max_revolutions = settle_max_revolutions;
                }
                ManyCase job;
                job.options =
                    run_options(c[1].cast<double>(), decimation, c[2].cast<double>(), max_output_bytes, settle);
                // The system objects stay alive in `cases` (held by the caller) for the whole call.
                if (py::isinstance<AnyMechanism>(c[0])) {
                    const AnyMechanism* a = &c[0].cast<const AnyMechanism&>();
                    job.run = [a, s, settle](const RunOptions& o) {
                        return a->visit(
                            [&](const auto& mech) { return output_of(mech, simulate(mech, s, o), settle); });
                    };
                } else {
                    throw py::type_error(detail::concat("systems[", i, "] must be a Mechanism, got ",
                                                        std::string(py::str(py::type::of(c[0]).attr("__name__")))));
                }
                jobs.push_back(std::move(job));
            }
            return run_many(jobs, threads, progress, progress_interval);
        },
        py::arg("cases"), py::arg("settings"), py::arg("decimation"), py::arg("max_output_bytes"), py::arg("threads"),
        py::arg("progress"), py::arg("progress_interval"), py::arg("settle_tolerance"),
        py::arg("settle_min_revolutions"), py::arg("settle_max_revolutions"),
        "Internal: camfollower.simulate_many() calls this with (system, duration, record_from, settle_period,\n"
        "settle_dofs) per case and wraps each output in a Result.");
}

}  // namespace camfollower::python
