// SPDX-License-Identifier: BSD-3-Clause
// Cross-section properties of a straight beam (a shaft segment), SI units.
//
// The material is given by E and the shear modulus G (not the Poisson ratio) so that a section of
// an anisotropic or measured material can be described directly; the circular factories take nu
// and set G = E / (2 (1 + nu)).
//
// Shear coefficients kappa are Cowper's: G. R. Cowper, "The shear coefficient in Timoshenko's
// beam theory", J. Appl. Mech. 33(2):335-340, 1966, Table 1:
//   solid circle   kappa = 6 (1 + nu) / (7 + 6 nu)
//   hollow circle  kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2),
//                  m = inner / outer diameter (m = 0 gives the solid circle).
#pragma once

#include <cmath>

#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"

namespace camfollower {

struct BeamSection {
    double youngs_modulus;       // E, Pa
    double shear_modulus;        // G, Pa
    double density;              // rho, kg/m^3
    double area;                 // A, m^2
    double second_moment_y;      // I_y = int z^2 dA, m^4: bending in the x-z plane (u_z, theta_y)
    double second_moment_z;      // I_z = int y^2 dA, m^4: bending in the x-y plane (u_y, theta_z)
    double polar_moment;         // torsion constant J, m^4 (= I_y + I_z for a circle or a tube)
    double shear_coefficient_y;  // kappa_y: effective shear area kappa_y A for shear along y
    double shear_coefficient_z;  // kappa_z: effective shear area kappa_z A for shear along z

    static BeamSection solid_circle(double diameter, double E, double nu, double rho) {
        return hollow_circle(diameter, 0.0, E, nu, rho);
    }

    static BeamSection hollow_circle(double outer, double inner, double E, double nu, double rho) {
        detail::require_length(outer, "outer diameter");
        detail::require_non_negative(inner, "inner diameter", "(m)");
        if (!(inner < outer)) detail::fail("inner diameter must be < outer diameter ", outer, " m, got ", inner);
        detail::require_positive(E, "youngs_modulus", "(Pa)");
        if (!(std::isfinite(nu) && nu >= 0.0 && nu < 0.5)) detail::fail("poisson_ratio must be in [0, 0.5), got ", nu);
        detail::require_positive(rho, "density", "(kg/m^3)");

        const double d4 = outer * outer * outer * outer - inner * inner * inner * inner;
        const double I = pi * d4 / 64.0;
        const double m2 = (inner / outer) * (inner / outer);
        const double kappa = 6.0 * (1.0 + nu) * (1.0 + m2) * (1.0 + m2) /
                             ((7.0 + 6.0 * nu) * (1.0 + m2) * (1.0 + m2) + (20.0 + 12.0 * nu) * m2);
        BeamSection s{
            E, E / (2.0 * (1.0 + nu)), rho, pi * (outer * outer - inner * inner) / 4.0, I, I, 2.0 * I, kappa, kappa};
        s.validate();
        return s;
    }

    void validate() const {
        detail::require_positive(youngs_modulus, "youngs_modulus", "(Pa)");
        detail::require_positive(shear_modulus, "shear_modulus", "(Pa)");
        detail::require_positive(density, "density", "(kg/m^3)");
        detail::require_positive(area, "area", "(m^2)");
        detail::require_positive(second_moment_y, "second_moment_y", "(m^4)");
        detail::require_positive(second_moment_z, "second_moment_z", "(m^4)");
        detail::require_positive(polar_moment, "polar_moment", "(m^4)");
        detail::require_positive(shear_coefficient_y, "shear_coefficient_y");
        detail::require_positive(shear_coefficient_z, "shear_coefficient_z");
    }
};

}  // namespace camfollower
