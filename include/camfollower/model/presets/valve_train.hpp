// SPDX-License-Identifier: BSD-3-Clause
// An inline engine's camshaft as a mechanism: one flexible, twisting camshaft (structure/shaft_spec.hpp)
// on radial bearings between the cylinders, driven at its front end through the timing drive's
// torsional compliance, carrying `valves_per_cylinder` cams per cylinder phased by the firing order;
// each cam lifts a roller tappet and valve (one mass) against a valve spring that surges (a chain of
// masses, structure/network.hpp). Names: cam "c<cylinder>v<valve>", its valve DOF
// "c<cylinder>v<valve>.valve", its spring "c<cylinder>v<valve>.spring", bearings "bearing<k>", the drive
// "drive", the shaft "camshaft" (x = 0 at the drive).
//
// The defaults describe a four-cylinder, four-valve head's intake camshaft (8 cams) with typical
// passenger-car sizes; they are an illustration, not a particular engine.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "camfollower/contact/line_contact.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/structure/beam_section.hpp"

namespace camfollower::presets {

struct ValveTrainParameters {
    int cylinders = 4;
    int valves_per_cylinder = 2;
    std::vector<int> firing_order{1, 3, 4, 2};  // empty: cylinders fire in order 1, 2, ...
    double engine_speed_rpm = 4000.0;           // the camshaft turns at half this

    // Camshaft: a hollow steel tube.
    double shaft_outer_diameter = 0.026, shaft_inner_diameter = 0.012;  // m
    double cylinder_pitch = 0.088;                                      // m, bore spacing
    double valve_pitch = 0.036;                                         // m, between a cylinder's two cams
    double max_element_length = 0.012;                                  // m
    double bearing_stiffness = 2e8, bearing_damping = 400.0;            // N/m, N s/m (radial, each bearing)
    double drive_stiffness = 6e3, drive_damping = 1.5;                  // N m/rad, N m s/rad (chain and sprocket)
    double sprocket_inertia = 1.5e-3;                                   // kg m^2
    double shaft_damping = 5e-6;  // s, stiffness-proportional (ratio ~1 % at the first torsional mode)

    // Cams (all the same profile): roller tappets on a dwell-rise-return-dwell program.
    double base_radius = 0.018, roller_radius = 0.009, roller_width = 0.012;  // m
    double lift = 0.009;                                                      // m
    double rise_angle = degrees_to_radians(70.0);                             // rad, rise = return
    double cam_width = 0.016, cam_mass = 0.09, cam_inertia = 1.8e-5;          // m, kg, kg m^2
    double contact_damping_factor = 0.0;                                      // s/m (Hunt-Crossley)

    // Valve, tappet and retainer as one mass; the valve spring with its own mass.
    double valve_mass = 0.085;                                // kg
    double valve_damping = 4.0;                               // N s/m (guide and oil)
    double spring_stiffness = 4.5e4, spring_preload = 280.0;  // N/m, N (valve closed)
    double spring_mass = 0.045, spring_damping = 2.5;         // kg, N s/m
    int spring_elements = 6;

    // m/s^2. The cams sit above their valves and lift them downwards: the frame's +z (the lift) is down.
    double gravity = 9.81;

    // The real-valued parameters by name with their SI unit (config files, Python); the integers
    // (cylinders, valves_per_cylinder, spring_elements) and firing_order are set directly.
    struct Field {
        const char* name;
        double ValveTrainParameters::*member;
        const char* unit;
    };
    static const std::vector<Field>& fields() {
        using P = ValveTrainParameters;
        static const std::vector<Field> table{
            {"shaft_outer_diameter", &P::shaft_outer_diameter, "m"},
            {"shaft_inner_diameter", &P::shaft_inner_diameter, "m"},
            {"cylinder_pitch", &P::cylinder_pitch, "m"},
            {"valve_pitch", &P::valve_pitch, "m"},
            {"max_element_length", &P::max_element_length, "m"},
            {"bearing_stiffness", &P::bearing_stiffness, "N/m"},
            {"bearing_damping", &P::bearing_damping, "N s/m"},
            {"drive_stiffness", &P::drive_stiffness, "N/m"},
            {"drive_damping", &P::drive_damping, "N s/m"},
            {"sprocket_inertia", &P::sprocket_inertia, "kg"},
            {"shaft_damping", &P::shaft_damping, "s"},
            {"base_radius", &P::base_radius, "m"},
            {"roller_radius", &P::roller_radius, "m"},
            {"roller_width", &P::roller_width, "m"},
            {"lift", &P::lift, "m"},
            {"rise_angle", &P::rise_angle, "rad"},
            {"cam_width", &P::cam_width, "m"},
            {"cam_mass", &P::cam_mass, "kg"},
            {"cam_inertia", &P::cam_inertia, "kg"},
            {"contact_damping_factor", &P::contact_damping_factor, "s/m"},
            {"valve_mass", &P::valve_mass, "kg"},
            {"valve_damping", &P::valve_damping, "N s/m"},
            {"spring_stiffness", &P::spring_stiffness, "N/m"},
            {"spring_preload", &P::spring_preload, "N"},
            {"spring_mass", &P::spring_mass, "kg"},
            {"spring_damping", &P::spring_damping, "N s/m"},
            {"gravity", &P::gravity, "m/s^2"},
        };
        return table;
    }

    // The real-valued field `name`, or an error listing every parameter (the integers and
    // firing_order included, which are set directly).
    double& ref(const std::string& name) {
        for (const Field& f : fields())
            if (name == f.name) return this->*(f.member);
        std::string known = "cylinders, valves_per_cylinder, spring_elements, firing_order";
        for (const Field& f : fields()) known += std::string(", ") + f.name;
        detail::fail("unknown valve-train parameter '", name, "'; known: ", known);
    }
    static const char* unit_of(const std::string& name) {
        for (const Field& f : fields())
            if (name == f.name) return f.unit;
        (void)ValveTrainParameters().ref(name);  // throws, listing the parameters
        return "";
    }

    double camshaft_speed() const { return 0.5 * engine_speed_rpm * two_pi / 60.0; }  // rad/s
    int cams() const { return cylinders * valves_per_cylinder; }

    void validate() const {
        if (cylinders < 1 || cylinders > 64) detail::fail("cylinders must be in [1, 64], got ", cylinders);
        if (valves_per_cylinder < 1 || valves_per_cylinder > 2)
            detail::fail("valves_per_cylinder must be 1 or 2 (on one camshaft), got ", valves_per_cylinder);
        if (!firing_order.empty()) {
            std::vector<int> sorted = firing_order;
            std::sort(sorted.begin(), sorted.end());
            for (int c = 1; c <= cylinders; ++c)
                if (int(sorted.size()) != cylinders || sorted[std::size_t(c - 1)] != c)
                    detail::fail("firing_order must list each cylinder 1..", cylinders, " once");
        }
        detail::require_positive(engine_speed_rpm, "engine_speed_rpm", "(rpm)");
        if (valves_per_cylinder == 2 && !(valve_pitch + cam_width <= cylinder_pitch))
            detail::fail("valve_pitch + cam_width = ", valve_pitch + cam_width,
                         " m must fit in cylinder_pitch = ", cylinder_pitch, " m");
        detail::require_in_range(rise_angle, 1e-3, pi - 1e-3, "rise_angle (rad)");
    }
};

// The camshaft's stations: bearings at the ends and between cylinders, cams about each cylinder's centre.
inline std::vector<double> valve_train_cam_stations(const ValveTrainParameters& p, int cylinder) {
    const double centre = (cylinder - 0.5) * p.cylinder_pitch;
    if (p.valves_per_cylinder == 1) return {centre};
    return {centre - 0.5 * p.valve_pitch, centre + 0.5 * p.valve_pitch};
}

inline MotionProgram valve_lift_program(const ValveTrainParameters& p) {
    const double b = p.rise_angle;
    return MotionProgram({{MotionLaw::dwell(), 0.0, pi - b, 0.0, 0.0},
                          {MotionLaw::polynomial_4567(), pi - b, pi, 0.0, p.lift},
                          {MotionLaw::polynomial_4567(), pi, pi + b, p.lift, 0.0},
                          {MotionLaw::dwell(), pi + b, two_pi, 0.0, 0.0}});
}

inline MechanismBuilder valve_train(const ValveTrainParameters& p = {}) {
    p.validate();
    const double length = p.cylinders * p.cylinder_pitch;
    std::vector<double> stations;
    for (int k = 0; k <= p.cylinders; ++k) stations.push_back(k * p.cylinder_pitch);
    for (int c = 1; c <= p.cylinders; ++c)
        for (double x : valve_train_cam_stations(p, c)) stations.push_back(x);
    MechanismBuilder b;
    b.add_shaft({"camshaft",
                 BeamSection::hollow_circle(p.shaft_outer_diameter, p.shaft_inner_diameter, 210e9, 0.3, 7850.0), length,
                 p.max_element_length, stations, false, p.shaft_damping});
    for (int k = 0; k <= p.cylinders; ++k)
        b.add_bearing("bearing" + std::to_string(k), "camshaft", k * p.cylinder_pitch, p.bearing_stiffness,
                      p.bearing_damping);
    b.add_drive("drive", "camshaft", 0.0, p.drive_stiffness, p.drive_damping);
    b.add_mass(b.structure.shaft_dof_at("camshaft", 0.0, 3), p.sprocket_inertia);
    b.set_gravity({0.0, 0.0, p.gravity});
    b.camshaft_speed = p.camshaft_speed();
    const MotionProgram program = valve_lift_program(p);
    const Eigen::Vector3d up(0.0, 0.0, 1.0);
    for (int c = 1; c <= p.cylinders; ++c) {
        // The cylinder's place in the firing order sets its phase: events 360 / cylinders cam degrees apart.
        int order = c - 1;
        if (!p.firing_order.empty())
            order = int(std::find(p.firing_order.begin(), p.firing_order.end(), c) - p.firing_order.begin());
        const double phase = -two_pi * order / p.cylinders;
        const std::vector<double> xs = valve_train_cam_stations(p, c);
        for (std::size_t v = 0; v < xs.size(); ++v) {
            const std::string name = "c" + std::to_string(c) + "v" + std::to_string(v + 1);
            b.add_dof(name + ".valve", p.valve_mass, up);
            b.add_damper(name + ".guide", name + ".valve", ground_name, p.valve_damping);
            b.add_spring_chain(name + ".spring", name + ".valve", ground_name, p.spring_stiffness, p.spring_mass,
                               p.spring_elements, p.spring_damping, p.spring_preload, up);
            ContactPairSpec cam{name,
                                program,
                                TranslatingRoller(p.base_radius, p.roller_radius, 0.0),
                                palmgren_law(p.roller_width, p.contact_damping_factor),
                                phase,
                                ground_name,
                                ground_name,
                                name + ".valve",
                                ground_name,
                                CamEccentricity{},
                                ground_name};
            b.mount_cam(cam, "camshaft", xs[v], p.cam_width, p.cam_mass, p.cam_inertia);
        }
    }
    return b;
}

}  // namespace camfollower::presets
