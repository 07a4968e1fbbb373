// SPDX-License-Identifier: BSD-3-Clause
// The 2-node, 12-DOF Timoshenko beam element along the x axis: stiffness with shear deformation and
// the consistent mass matrix with rotary inertia.
//
// Reference: J. S. Przemieniecki, "Theory of Matrix Structural Analysis", McGraw-Hill 1968 (Dover
// 1985): the stiffness of the beam element with shear deformation (ch. 5) and its consistent mass
// matrix with shear deformation and rotary inertia (ch. 11). Both follow from the cubic/quadratic
// interpolation that solves the static Timoshenko equations exactly (the same interpolation as
// Friedman & Kosmatka, Comput. Struct. 47(3):473-481, 1993), so the element reproduces the exact
// static deflection of an end-loaded beam with a single element.
//
// DOFs, node-major, 6 per node (node 1: 0..5, node 2: 6..11):
//   u_x axial, u_y, u_z, theta_x torsion, theta_y, theta_z  (right-handed rotations about the axes).
// For the Euler-Bernoulli limit theta_z = +du_y/dx and theta_y = -du_z/dx, so theta_z couples with
// u_y positively and theta_y with u_z negatively. The rotations are those of the cross-section
// (Timoshenko's psi), which differ from the slope of the axis by the shear angle.
//
// Shear parameter of a plane: phi = 12 E I / (kappa G A L^2); x-y plane (u_y, theta_z) uses I_z and
// kappa_y, x-z plane (u_z, theta_y) uses I_y and kappa_z. Torsion is Saint-Venant (G J, no warping);
// its rotary inertia is rho (I_y + I_z), the polar moment of area, which equals rho J for circles.
// Axial and torsional parts use linear interpolation (consistent mass rho A L / 6 [2 1; 1 2]).
#pragma once

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/structure/beam_section.hpp"

namespace camfollower {

using BeamMatrix = Eigen::Matrix<double, 12, 12>;

namespace detail {

// Bending in one plane, DOFs (v1, theta1, v2, theta2) with theta = +dv/dx in the slender limit.
inline Eigen::Matrix4d planar_bending_stiffness(double EI, double phi, double L) {
    Eigen::Matrix4d k;
    const double L2 = L * L;
    k << 12.0, 6.0 * L, -12.0, 6.0 * L, 6.0 * L, (4.0 + phi) * L2, -6.0 * L, (2.0 - phi) * L2, -12.0, -6.0 * L, 12.0,
        -6.0 * L, 6.0 * L, (2.0 - phi) * L2, -6.0 * L, (4.0 + phi) * L2;
    return k * (EI / ((1.0 + phi) * L * L2));
}

// Translational (rho A) plus rotary (rho I) inertia; Przemieniecki ch. 11.
inline Eigen::Matrix4d planar_bending_mass(double rhoA, double rhoI, double phi, double L) {
    const double p = phi, p2 = phi * phi, L2 = L * L;
    const double t11 = 13.0 / 35.0 + 7.0 * p / 10.0 + p2 / 3.0;
    const double t12 = (11.0 / 210.0 + 11.0 * p / 120.0 + p2 / 24.0) * L;
    const double t13 = 9.0 / 70.0 + 3.0 * p / 10.0 + p2 / 6.0;
    const double t14 = -(13.0 / 420.0 + 3.0 * p / 40.0 + p2 / 24.0) * L;
    const double t22 = (1.0 / 105.0 + p / 60.0 + p2 / 120.0) * L2;
    const double t24 = -(1.0 / 140.0 + p / 60.0 + p2 / 120.0) * L2;
    Eigen::Matrix4d translational;
    translational << t11, t12, t13, t14, t12, t22, -t14, t24, t13, -t14, t11, -t12, t14, t24, -t12, t22;

    const double r11 = 6.0 / 5.0;
    const double r12 = (1.0 / 10.0 - p / 2.0) * L;
    const double r22 = (2.0 / 15.0 + p / 6.0 + p2 / 3.0) * L2;
    const double r24 = (-1.0 / 30.0 - p / 6.0 + p2 / 6.0) * L2;
    Eigen::Matrix4d rotary;
    rotary << r11, r12, -r11, r12, r12, r22, -r12, r24, -r11, -r12, r11, -r12, r12, r24, -r12, r22;

    const double scale = 1.0 / ((1.0 + phi) * (1.0 + phi));
    return translational * (scale * rhoA * L) + rotary * (scale * rhoI / L);
}

// Places a planar 4x4 block on element DOFs (v1, theta1, v2, theta2); sign -1 flips the rotation
// (x-z plane, where theta_y = -du_z/dx).
inline void place_bending_block(BeamMatrix& element, const Eigen::Matrix4d& block, int v, int theta, double sign) {
    const int index[4] = {v, theta, v + 6, theta + 6};
    const double flip[4] = {1.0, sign, 1.0, sign};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) element(index[i], index[j]) += flip[i] * flip[j] * block(i, j);
}

// Two-node bar block c [1 -1; -1 1] or c/6 [2 1; 1 2] on element DOF `dof` of both nodes.
inline void place_bar_block(BeamMatrix& element, int dof, double diagonal, double off_diagonal) {
    element(dof, dof) += diagonal;
    element(dof + 6, dof + 6) += diagonal;
    element(dof, dof + 6) += off_diagonal;
    element(dof + 6, dof) += off_diagonal;
}

inline double shear_parameter(double EI, double kappa, double G, double A, double L) {
    return 12.0 * EI / (kappa * G * A * L * L);
}

}  // namespace detail

// Element stiffness (N/m, N, N m/rad mixed as the DOFs require) of a beam of the given length (m).
inline BeamMatrix timoshenko_stiffness(const BeamSection& s, double length) {
    s.validate();
    detail::require_positive(length, "element length", "(m)");
    const double L = length, E = s.youngs_modulus, G = s.shear_modulus, A = s.area;
    BeamMatrix k = BeamMatrix::Zero();
    detail::place_bar_block(k, 0, E * A / L, -E * A / L);
    detail::place_bar_block(k, 3, G * s.polar_moment / L, -G * s.polar_moment / L);
    const double phi_y = detail::shear_parameter(E * s.second_moment_z, s.shear_coefficient_y, G, A, L);
    const double phi_z = detail::shear_parameter(E * s.second_moment_y, s.shear_coefficient_z, G, A, L);
    detail::place_bending_block(k, detail::planar_bending_stiffness(E * s.second_moment_z, phi_y, L), 1, 5, +1.0);
    detail::place_bending_block(k, detail::planar_bending_stiffness(E * s.second_moment_y, phi_z, L), 2, 4, -1.0);
    return k;
}

// Consistent element mass (kg, kg m, kg m^2 as the DOFs require).
inline BeamMatrix timoshenko_mass(const BeamSection& s, double length) {
    s.validate();
    detail::require_positive(length, "element length", "(m)");
    const double L = length, E = s.youngs_modulus, G = s.shear_modulus, A = s.area, rho = s.density;
    BeamMatrix m = BeamMatrix::Zero();
    detail::place_bar_block(m, 0, rho * A * L / 3.0, rho * A * L / 6.0);
    const double polar_inertia = rho * (s.second_moment_y + s.second_moment_z);
    detail::place_bar_block(m, 3, polar_inertia * L / 3.0, polar_inertia * L / 6.0);
    const double phi_y = detail::shear_parameter(E * s.second_moment_z, s.shear_coefficient_y, G, A, L);
    const double phi_z = detail::shear_parameter(E * s.second_moment_y, s.shear_coefficient_z, G, A, L);
    detail::place_bending_block(m, detail::planar_bending_mass(rho * A, rho * s.second_moment_z, phi_y, L), 1, 5, +1.0);
    detail::place_bending_block(m, detail::planar_bending_mass(rho * A, rho * s.second_moment_y, phi_z, L), 2, 4, -1.0);
    return m;
}

}  // namespace camfollower
