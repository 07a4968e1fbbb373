// SPDX-License-Identifier: BSD-3-Clause
// The runtime description of a mechanism: its linear structure (structure/network.hpp), camshafts
// with bearings, drives and mounted cams, and its nonlinear elements' specs (cam-follower contacts,
// clearances). Mutable; Mechanism<N>(builder) (model/mechanism.hpp) makes the immutable model.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "camfollower/contact/clearance.hpp"
#include "camfollower/contact/conjugate.hpp"
#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/error.hpp"
#include "camfollower/linkage/coupler_linkage.hpp"
#include "camfollower/motion/speed_program.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

// The runtime description of a mechanism (mutable; Mechanism<N>(builder) makes the immutable model).
struct MechanismBuilder {
    NetworkSpec structure;
    std::vector<ContactPairSpec> contacts;
    std::vector<ClearanceSpec> clearances;
    std::vector<PinJointSpec> pin_joints;
    std::vector<CouplerLinkage> linkages;           // as added (their coupler DOFs and joints are in the lists above)
    double camshaft_speed = 750.0 * two_pi / 60.0;  // rad/s; with a speed program its nominal speed
    // A variable camshaft speed (motion/speed_program.hpp; none: constant camshaft_speed). The
    // program's speeds are scaled so that its nominal speed is camshaft_speed: changing the speed
    // (a study's sweep) scales the whole program.
    std::optional<SpeedProgram> speed_program;

    // The structure's elements (structure/network.hpp), by DOF name ("ground" for the frame).
    void add_dof(const std::string& name, double mass, const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        structure.add_dof(name, mass, direction);
    }
    void add_spring(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                    double damping = 0.0, double preload = 0.0) {
        require_unused_name(name, "element");
        structure.add_spring(name, a, b, stiffness, damping, preload);
    }
    void add_damper(const std::string& name, const std::string& a, const std::string& b, double damping) {
        structure.add_spring(name, a, b, 0.0, damping, 0.0);
    }
    void add_load(const std::string& dof, double force) { structure.add_load(dof, force); }
    void set_gravity(const Eigen::Vector3d& g) { structure.set_gravity(g); }
    void set_rayleigh_damping(double alpha, double beta) { structure.set_rayleigh_damping(alpha, beta); }
    void set_modal_damping(const std::vector<double>& ratios) { structure.set_modal_damping(ratios); }

    void add_contact(const ContactPairSpec& c) {
        detail::require_name(c.name, "contact");
        require_unused_name(c.name, "contact");
        c.require_distinct_roles();
        contacts.push_back(c);
    }
    // Conjugate cams (contact/conjugate.hpp): the contacts "<name>.lift" and "<name>.return".
    void add_conjugate_cams(const ConjugateCams& c) {
        for (const ContactPairSpec& pair : c.contacts()) add_contact(pair);
    }
    // A radial clearance (contact/clearance.hpp); add_guide adds one per bushing.
    void add_clearance(const ClearanceSpec& c) {
        c.validate();
        require_unused_name(c.name, "clearance");
        clearances.push_back(c);
    }
    void add_guide(const GuideSpec& g) {
        for (const ClearanceSpec& c : g.clearances()) add_clearance(c);
    }
    // A pin joint between two points of two links (linkage/coupler_linkage.hpp).
    void add_pin_joint(const PinJointSpec& j) {
        j.validate();
        require_unused_name(j.name, "pin joint");
        pin_joints.push_back(j);
    }
    // A cam-driven linkage (linkage/coupler_linkage.hpp): the coupler's DOFs <name>.x, <name>.y (its
    // mass) and <name>.angle (its inertia about its centre), and the pin joints <name>.input (arm's
    // pin to the coupler) and <name>.output (coupler to the output's pin), assembled at q = 0.
    void add_linkage(const CouplerLinkage& l) {
        l.validate();
        require_unused_name(l.name, "linkage");
        for (const CouplerLinkage& o : linkages)
            if (o.name == l.name) detail::fail("linkage '", l.name, "' is defined twice");
        const Eigen::Vector2d A = l.arm_pin_at(0.0), B = l.output_pin(0.0), centre = 0.5 * (A + B);
        const double angle = std::atan2(B.y() - A.y(), B.x() - A.x()), half = 0.5 * l.coupler_length;
        const std::array<std::string, 3> body{l.name + ".x", l.name + ".y", l.name + ".angle"};
        add_dof(body[0], l.coupler_mass);
        add_dof(body[1], l.coupler_mass);
        add_dof(body[2], l.coupler_inertia);
        add_pin_joint(
            {l.name + ".input",
             PlanarPoint::on_rotating(l.arm_dof, l.arm_pivot, l.arm_length, l.arm_angle, turn_sign(l.arm_turn)),
             PlanarPoint::on_body(body, centre, angle, {-half, 0.0}), l.joint_stiffness, l.joint_damping});
        const Eigen::Vector2d from_pivot = B - l.output_origin;
        const PlanarPoint output =
            l.output == CouplerLinkage::Output::slider
                ? PlanarPoint::on_slider(l.output_dof, B, l.output_direction)
                : PlanarPoint::on_rotating(l.output_dof, l.output_origin, l.output_length,
                                           std::atan2(from_pivot.y(), from_pivot.x()), turn_sign(l.output_turn));
        add_pin_joint({l.name + ".output", PlanarPoint::on_body(body, centre, angle, {half, 0.0}), output,
                       l.joint_stiffness, l.joint_damping});
        linkages.push_back(l);
    }
    // --- flexible camshafts (structure/shaft_spec.hpp); the shaft's axis is the global x axis, a cam's
    // contact frame has its x along global y and its y (a translating follower's axis) along global z.
    void add_shaft(const ShaftSpec& shaft) { structure.add_shaft(shaft); }

    // A bearing at station x: radial spring-dampers from u_y and u_z to ground ("<name>.y", "<name>.z").
    void add_bearing(const std::string& name, const std::string& shaft, double x, double radial_stiffness,
                     double radial_damping = 0.0) {
        const int node = structure.shaft(shaft).spec.node_at(x);
        for (const Mount& b : bearings_)
            if (b.shaft == shaft && b.node == node)
                detail::fail("bearings '", b.name, "' and '", name, "' are at the same station x = ", x,
                             " m of shaft '", shaft, "'");
        detail::require_positive(radial_stiffness, ("radial stiffness of bearing '" + name + "'").c_str(), "(N/m)");
        add_spring(name + ".y", structure.shaft_dof_at(shaft, x, 1), ground_name, radial_stiffness, radial_damping);
        add_spring(name + ".z", structure.shaft_dof_at(shaft, x, 2), ground_name, radial_stiffness, radial_damping);
        bearings_.push_back({name, shaft, x, node, 0.0});
    }

    // The drive as an imposed speed through a compliance: a torsional spring-damper (N m/rad, N m s/rad)
    // from the shaft's twist at station x to the rigid rotation (the camshaft's speed program).
    void add_drive(const std::string& name, const std::string& shaft, double x, double stiffness,
                   double damping = 0.0) {
        detail::require_positive(stiffness, ("stiffness of drive '" + name + "'").c_str(), "(N m/rad)");
        add_spring(name, structure.shaft_dof_at(shaft, x, 3), ground_name, stiffness, damping);
    }

    // The drive as a speed-controlled motor with a flywheel at station x: the flywheel's inertia
    // (kg m^2) on the twist, the controller's position gain (N m/rad, > 0: it holds the shaft's angle
    // to the nominal rotation, so a static equilibrium exists) and velocity gain (N m s/rad), and a
    // constant torque (N m, forward: the cams' mean torque as feed-forward).
    void add_motor(const std::string& name, const std::string& shaft, double x, double inertia, double position_gain,
                   double velocity_gain, double torque) {
        const std::string twist = structure.shaft_dof_at(shaft, x, 3);
        detail::require_positive(position_gain, ("position_gain of motor '" + name + "'").c_str(),
                                 "(N m/rad; a motor without one leaves the shaft's angle free)");
        detail::require_non_negative(velocity_gain, ("velocity_gain of motor '" + name + "'").c_str(), "(N m s/rad)");
        detail::require_finite(torque, ("torque of motor '" + name + "'").c_str());
        add_mass(twist, inertia);
        add_spring(name, twist, ground_name, position_gain, velocity_gain);
        if (torque != 0.0) add_load(twist, torque);
    }

    // A cam mounted at station x of a shaft: the contact's cam centre and twist become the node's u_y,
    // u_z and theta_x (a barrel cam's, its follower on the +z side: u_y across the station and the
    // axial u_x, which the shaft must model); the cam's mass (kg) and inertia (kg m^2) are added there; `width` (m) is
    // its axial extent, checked against the other cams on the shaft.
    void mount_cam(ContactPairSpec contact, const std::string& shaft, double x, double width = 0.0, double mass = 0.0,
                   double inertia = 0.0) {
        const ShaftEntry& s = structure.shaft(shaft);
        if (!(std::isfinite(x) && x >= 0.0 && x <= s.spec.length))
            detail::fail("cam '", contact.name, "' at x = ", x, " m is outside shaft '", shaft, "' [0, ", s.spec.length,
                         "] m");
        detail::require_non_negative(width, ("width of cam '" + contact.name + "'").c_str(), "(m)");
        detail::require_non_negative(mass, ("mass of cam '" + contact.name + "'").c_str(), "(kg)");
        detail::require_non_negative(inertia, ("inertia of cam '" + contact.name + "'").c_str(), "(kg m^2)");
        if (x - 0.5 * width < -ShaftSpec::merge_distance || x + 0.5 * width > s.spec.length + ShaftSpec::merge_distance)
            detail::fail("cam '", contact.name, "' (x = ", x, " m, width ", width,
                         " m) reaches past the ends of shaft '", shaft, "'");
        const int node = s.spec.node_at(x);
        for (const Mount& o : cams_)
            if (o.shaft == shaft && (o.node == node || std::abs(o.x - x) < 0.5 * (o.width + width)))
                detail::fail("cams '", o.name, "' (x = ", o.x, " m, width ", o.width, " m) and '", contact.name,
                             "' (x = ", x, " m, width ", width, " m) overlap on shaft '", shaft, "'");
        const bool barrel = is_barrel(contact.follower);
        if (barrel && !s.spec.axial)
            detail::fail("barrel cam '", contact.name, "' on shaft '", shaft,
                         "': its follower's load is along the shaft, so the shaft needs its axial DOFs (axial = true)");
        contact.cam_x = structure.shaft_dof_at(shaft, x, 1);
        contact.cam_y = structure.shaft_dof_at(shaft, x, barrel ? 0 : 2);
        contact.cam_twist = structure.shaft_dof_at(shaft, x, 3);
        add_contact(contact);
        if (mass > 0.0) {
            add_mass(structure.shaft_dof_at(shaft, x, 1), mass);
            add_mass(structure.shaft_dof_at(shaft, x, 2), mass);
            if (barrel) add_mass(structure.shaft_dof_at(shaft, x, 0), mass);
        }
        if (inertia > 0.0) add_mass(contact.cam_twist, inertia);
        cams_.push_back({contact.name, shaft, x, node, width});
    }
    void add_mass(const std::string& dof, double mass) { structure.add_mass(dof, mass); }
    void add_spring_chain(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                          double mass, int elements, double damping = 0.0, double preload = 0.0,
                          const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        require_unused_name(name, "element");
        structure.add_spring_chain(name, a, b, stiffness, mass, elements, damping, preload, direction);
    }

    void set_camshaft_speed_rpm(double rpm) {
        detail::require_camshaft_speed_rpm(rpm, "camshaft_speed_rpm");
        camshaft_speed = rpm * two_pi / 60.0;
    }
    double camshaft_speed_rpm() const { return camshaft_speed * 60.0 / two_pi; }
    // Drive the camshaft by a speed program; camshaft_speed becomes its nominal speed.
    void set_speed_program(const SpeedProgram& program) {
        speed_program = program;
        camshaft_speed = program.nominal_speed();
    }
    // The camshaft's rotation as built: the speed program at camshaft_speed, or that constant speed.
    SpeedProgram drive() const {
        detail::require_camshaft_speed(camshaft_speed, "camshaft_speed");
        return speed_program ? speed_program->scaled_to(camshaft_speed) : SpeedProgram::constant(camshaft_speed);
    }

private:
    // Elements name their channels ("<name>.force", ...): one name, one element, whatever its kind.
    void require_unused_name(const std::string& name, const char* kind) const {
        for (const ContactPairSpec& c : contacts)
            if (c.name == name) detail::fail(kind, " '", name, "': the name is taken by contact '", name, "'");
        for (const ClearanceSpec& c : clearances)
            if (c.name == name) detail::fail(kind, " '", name, "': the name is taken by clearance '", name, "'");
        for (const PinJointSpec& j : pin_joints)
            if (j.name == name) detail::fail(kind, " '", name, "': the name is taken by pin joint '", name, "'");
        for (const SpringSpec& s : structure.springs())
            if (s.name == name) detail::fail(kind, " '", name, "': the name is taken by element '", name, "'");
    }

    struct Mount {
        std::string name, shaft;
        double x;
        int node;
        double width;
    };
    std::vector<Mount> cams_, bearings_;
};

}  // namespace camfollower
