// SPDX-License-Identifier: BSD-3-Clause
// The paper preset's parameter card (presets/paper.hpp): Table 2 defaults, settable by name, validated.
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "camfollower/error.hpp"
#include "camfollower/motion/program.hpp"  // two_pi

namespace camfollower {

// The paper's cam and roller (Table 1): base radius, roller radius and follower offset, m.
struct PaperCamGeometry {
    double base_radius = 0.030;    // r_b (paper: 2 R_a = 60 mm)
    double roller_radius = 0.008;  // r_r (paper: 2 R_1 = 16 mm)
    double offset = 0.010;         // e
};

enum class ContactDampingModel { none, hunt_crossley, lankarani_nikravesh };

struct CamFollowerParameters {
    // Masses, kg (paper Table 2). The paper gives no camshaft mass: m_c is derived so that the
    // contact-free camshaft bearing mode sits at Table 3's degenerate 2447 Hz pair,
    // m_c = K_vs / (2 pi 2447 Hz)^2 (see docs/model.md).
    double camshaft_mass = 2.6e8 / ((2.0 * pi * 2447.0) * (2.0 * pi * 2447.0));
    double roller_mass = 0.07;         // M_fc
    double follower_rod_mass = 0.340;  // M_f
    double follower_mass = 1.36;       // M_eq (follower top, spring seat)
    // Stiffness, N/m; damping, N s/m.
    double bearing_stiffness_vertical = 2.6e8;       // K_vs
    double bearing_stiffness_horizontal = 2.6e8;     // K_hs
    double bearing_damping_vertical = 750.0;         // C_vs
    double bearing_damping_horizontal = 750.0;       // C_hs
    double contact_stiffness = 1.9e8;                // K_h, N/m^n
    double contact_exponent = 1.0;                   // n: 1 (paper), 1.5 (point), 10/9 (line)
    double roller_pin_stiffness_vertical = 1.7e8;    // K_vc
    double roller_pin_stiffness_horizontal = 2.5e8;  // K_hc
    double guide_stiffness = 2.5e8;                  // K_rb, rod guide, lateral
    double rod_stiffness = 2.5e8;                    // K_f, rod axial
    double rod_damping = 0.08;                       // C_f
    double spring_stiffness = 1.4e4;                 // K_rs, return spring
    double spring_preload_deflection = 0.013;        // delta_rs, m
    double gravity = 0.0;                            // m/s^2 along -y; 0 = off (paper)
    // Optional contact damping F = K_h delta^n (1 + chi delta_dot), chi from the restitution
    // coefficient and a reference impact speed.
    ContactDampingModel contact_damping = ContactDampingModel::none;
    double restitution = 1.0;      // c_e in [0, 1]
    double reference_speed = 1.0;  // m/s
    // Kinematics.
    double camshaft_speed_rpm = 750.0;
    PaperCamGeometry geometry{};

    double omega() const { return camshaft_speed_rpm * two_pi / 60.0; }

    // chi (s/m) of the contact damping law.
    double contact_damping_factor() const {
        switch (contact_damping) {
            case ContactDampingModel::hunt_crossley: return 3.0 * (1.0 - restitution) / (2.0 * reference_speed);
            case ContactDampingModel::lankarani_nikravesh:
                return 3.0 * (1.0 - restitution * restitution) / (4.0 * reference_speed);
            case ContactDampingModel::none: break;
        }
        return 0.0;
    }

    // Every scalar parameter by name, for overriding from Python or a config file.
    struct Field {
        const char* name;
        double CamFollowerParameters::*member;
        const char* unit;
    };
    static const std::array<Field, 24>& fields() {
        using P = CamFollowerParameters;
        static const std::array<Field, 24> table{{
            {"camshaft_mass", &P::camshaft_mass, "kg"},
            {"roller_mass", &P::roller_mass, "kg"},
            {"follower_rod_mass", &P::follower_rod_mass, "kg"},
            {"follower_mass", &P::follower_mass, "kg"},
            {"bearing_stiffness_vertical", &P::bearing_stiffness_vertical, "N/m"},
            {"bearing_stiffness_horizontal", &P::bearing_stiffness_horizontal, "N/m"},
            {"bearing_damping_vertical", &P::bearing_damping_vertical, "N s/m"},
            {"bearing_damping_horizontal", &P::bearing_damping_horizontal, "N s/m"},
            {"contact_stiffness", &P::contact_stiffness, "N/m^n"},
            {"contact_exponent", &P::contact_exponent, "-"},
            {"roller_pin_stiffness_vertical", &P::roller_pin_stiffness_vertical, "N/m"},
            {"roller_pin_stiffness_horizontal", &P::roller_pin_stiffness_horizontal, "N/m"},
            {"guide_stiffness", &P::guide_stiffness, "N/m"},
            {"rod_stiffness", &P::rod_stiffness, "N/m"},
            {"rod_damping", &P::rod_damping, "N s/m"},
            {"spring_stiffness", &P::spring_stiffness, "N/m"},
            {"spring_preload_deflection", &P::spring_preload_deflection, "m"},
            {"gravity", &P::gravity, "m/s^2"},
            {"restitution", &P::restitution, "-"},
            {"reference_speed", &P::reference_speed, "m/s"},
            {"camshaft_speed_rpm", &P::camshaft_speed_rpm, "rpm"},
            {"base_radius", nullptr, "m"},
            {"roller_radius", nullptr, "m"},
            {"offset", nullptr, "m"},
        }};
        return table;
    }

    double& ref(const std::string& name) {
        if (name == "base_radius") return geometry.base_radius;
        if (name == "roller_radius") return geometry.roller_radius;
        if (name == "offset") return geometry.offset;
        for (const Field& f : fields())
            if (f.member && name == f.name) return this->*(f.member);
        std::string known;
        for (const Field& f : fields()) known += std::string(known.empty() ? "" : ", ") + f.name;
        detail::fail("unknown parameter '", name, "'; known parameters: ", known);
    }
    double get(const std::string& name) const { return const_cast<CamFollowerParameters*>(this)->ref(name); }
    void set(const std::string& name, double value) {
        double& slot = ref(name);
        const double old = slot;
        slot = value;
        try {
            validate();
        } catch (...) {
            slot = old;
            throw;
        }
    }

    void validate() const {
        using detail::require_non_negative;
        using detail::require_positive;
        require_positive(camshaft_mass, "camshaft_mass", "(kg)");
        require_positive(roller_mass, "roller_mass", "(kg)");
        require_positive(follower_rod_mass, "follower_rod_mass", "(kg)");
        require_positive(follower_mass, "follower_mass", "(kg)");
        for (const Field& f : fields()) {
            if (!f.member) continue;
            const double v = this->*(f.member);
            if (!std::isfinite(v)) detail::fail(f.name, " must be finite (", f.unit, "), got ", v);
        }
        // Every spring holds a body in place (a zero one leaves a free mode and no equilibrium); the
        // preload keeps the follower on the cam. Dampers may be zero.
        for (const char* name :
             {"bearing_stiffness_vertical", "bearing_stiffness_horizontal", "roller_pin_stiffness_vertical",
              "roller_pin_stiffness_horizontal", "guide_stiffness", "rod_stiffness", "spring_stiffness"})
            require_positive(get(name), name);
        detail::require_length(spring_preload_deflection, "spring_preload_deflection");
        for (const char* name : {"bearing_damping_vertical", "bearing_damping_horizontal", "rod_damping"})
            require_non_negative(get(name), name);
        require_positive(contact_stiffness, "contact_stiffness", "(N/m^n)");
        detail::require_in_range(contact_exponent, 1.0, 3.0, "contact_exponent");
        detail::require_in_range(restitution, 0.0, 1.0, "restitution");
        require_positive(reference_speed, "reference_speed", "(m/s)");
        // chi (1 - c_e) / v_ref: above 1e6 s/m the damping would match the elastic force at penetration
        // rates of um/s, a reference speed far below any impact's.
        if (!(contact_damping_factor() <= 1e6))
            detail::fail("reference_speed = ", reference_speed,
                         " m/s gives the contact damping factor chi = ", contact_damping_factor(),
                         " s/m (allowed: <= 1e6; chi grows as (1 - restitution) / "
                         "reference_speed): give the contact's typical impact speed, of the order of 0.01 to 1 m/s");
        require_non_negative(gravity, "gravity", "(m/s^2)");
        detail::require_camshaft_speed_rpm(camshaft_speed_rpm, "camshaft_speed_rpm");
        detail::require_length(geometry.base_radius, "base_radius");
        detail::require_length(geometry.roller_radius, "roller_radius");
        const double rp = geometry.base_radius + geometry.roller_radius;
        if (!(std::isfinite(geometry.offset) && std::abs(geometry.offset) < rp))
            detail::fail("offset must satisfy |offset| < base_radius + roller_radius = ", rp, " m, got ",
                         geometry.offset, " m");
    }
};

}  // namespace camfollower
