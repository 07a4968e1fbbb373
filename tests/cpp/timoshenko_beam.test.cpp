// SPDX-License-Identifier: BSD-3-Clause
// The Timoshenko shaft element and its assembly against independent truth: the element matrices
// re-derived here by Gauss quadrature of the exact static (Przemieniecki / Friedman-Kosmatka)
// interpolation, rigid-body properties, closed-form static deflections (exact for this element),
// and natural frequencies from the Euler-Bernoulli, rod-torsion and Timoshenko closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "angles.hpp"
#include "camfollower/structure/beam_section.hpp"
#include "camfollower/structure/shaft_assembly.hpp"
#include "camfollower/structure/timoshenko_beam.hpp"

using namespace camfollower;
using Catch::Matchers::Contains;

namespace {
const double E_steel = 210e9, nu_steel = 0.3, rho_steel = 7850.0;
const double G_steel = E_steel / (2.0 * (1.0 + nu_steel));
// Cowper (1966) solid circle.
const double kappa_solid = 6.0 * (1.0 + nu_steel) / (7.0 + 6.0 * nu_steel);

double circle_area(double d) { return PI * d * d / 4.0; }
double circle_I(double d) { return PI * d * d * d * d / 64.0; }

// Euler-Bernoulli simply supported: omega_n = (n pi / L)^2 sqrt(E I / (rho A)).
double euler_bernoulli_ss_hz(int n, double L, double d) {
    const double k = n * PI / L;
    return k * k * std::sqrt(E_steel * circle_I(d) / (rho_steel * circle_area(d))) / (2.0 * PI);
}

// Timoshenko simply supported, mode n: w = W sin(k x), psi = Psi cos(k x), k = n pi / L, in
//   kappa G A (w'' - psi') = rho A w_tt,   E I psi'' + kappa G A (w' - psi) = rho I psi_tt
// gives (kGA k^2 - rho A w2)(E I k^2 + kGA - rho I w2) - (kGA k)^2 = 0, a quadratic in w2 = omega^2;
// the bending branch is its lower root (taken in the cancellation-free form 2c / (b + sqrt)).
double timoshenko_ss_hz(int n, double L, double d) {
    const double A = circle_area(d), I = circle_I(d), kGA = kappa_solid * G_steel * A;
    const double k = n * PI / L;
    const double a = rho_steel * A * rho_steel * I;
    const double b = rho_steel * A * (E_steel * I * k * k + kGA) + rho_steel * I * kGA * k * k;
    const double c = kGA * k * k * E_steel * I * k * k;
    const double omega2 = 2.0 * c / (b + std::sqrt(b * b - 4.0 * a * c));
    return std::sqrt(omega2) / (2.0 * PI);
}

// All DOFs except the listed ones, at every node: restricts a shaft to one kind of motion.
std::vector<int> all_but(const UniformShaft& shaft, std::vector<ShaftDof> keep) {
    std::vector<int> fixed;
    for (int node = 0; node < shaft.node_count(); ++node)
        for (int d = 0; d < shaft_dofs_per_node; ++d) {
            bool kept = false;
            for (ShaftDof k : keep) kept = kept || static_cast<int>(k) == d;
            if (!kept) fixed.push_back(shaft_dofs_per_node * node + d);
        }
    return fixed;
}

// Natural frequencies in Hz, ascending, of the shaft with the fixed DOFs removed.
Eigen::VectorXd frequencies_hz(const UniformShaft& shaft, const std::vector<int>& fixed) {
    const Eigen::MatrixXd K = remove_dofs(shaft.stiffness(), fixed);
    const Eigen::MatrixXd M = remove_dofs(shaft.mass(), fixed);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M, Eigen::EigenvaluesOnly);
    REQUIRE(solver.info() == Eigen::Success);
    return solver.eigenvalues().cwiseMax(0.0).cwiseSqrt() / (2.0 * PI);
}

// Simply supported in the x-y plane: u_y = 0 at both ends, theta_z free.
std::vector<int> simply_supported_xy(const UniformShaft& shaft) {
    std::vector<int> fixed = all_but(shaft, {ShaftDof::lateral_y, ShaftDof::rotation_z});
    fixed.push_back(shaft_dof(0, ShaftDof::lateral_y));
    fixed.push_back(shaft_dof(shaft.element_count(), ShaftDof::lateral_y));
    return fixed;
}

std::vector<int> clamped_at_node_zero() { return {0, 1, 2, 3, 4, 5}; }

Eigen::VectorXd solve_static(const UniformShaft& shaft, const std::vector<int>& fixed, const Eigen::VectorXd& load) {
    const Eigen::MatrixXd K = remove_dofs(shaft.stiffness(), fixed);
    const Eigen::VectorXd reduced = Eigen::LDLT<Eigen::MatrixXd>(K).solve(remove_dofs(load, fixed));
    Eigen::VectorXd full = Eigen::VectorXd::Zero(shaft.dof_count());
    const std::vector<int> kept = kept_dofs(shaft.dof_count(), fixed);
    for (std::size_t i = 0; i < kept.size(); ++i) full(kept[i]) = reduced(static_cast<Eigen::Index>(i));
    return full;
}

// The exact static interpolation of the Timoshenko beam (Przemieniecki; Friedman & Kosmatka 1993),
// DOFs (v1, psi1, v2, psi2), xi = x / L: deflection N and section rotation Psi.
struct PlanarShape {
    Eigen::Vector4d N, dN, Psi, dPsi;
};
PlanarShape planar_shape(double xi, double L, double phi) {
    const double s = 1.0 / (1.0 + phi);
    PlanarShape f;
    f.N << s * (2 * xi * xi * xi - 3 * xi * xi - phi * xi + 1 + phi),
        s * L * (xi * xi * xi - (2 + phi / 2) * xi * xi + (1 + phi / 2) * xi),
        s * (-2 * xi * xi * xi + 3 * xi * xi + phi * xi),
        s * L * (xi * xi * xi - (1 - phi / 2) * xi * xi - phi / 2 * xi);
    f.dN << s * (6 * xi * xi - 6 * xi - phi) / L, s * (3 * xi * xi - (4 + phi) * xi + 1 + phi / 2),
        s * (-6 * xi * xi + 6 * xi + phi) / L, s * (3 * xi * xi - (2 - phi) * xi - phi / 2);
    f.Psi << s * 6 * (xi * xi - xi) / L, s * (3 * xi * xi - (4 + phi) * xi + 1 + phi), -s * 6 * (xi * xi - xi) / L,
        s * (3 * xi * xi - (2 - phi) * xi);
    f.dPsi << s * 6 * (2 * xi - 1) / (L * L), s * (6 * xi - (4 + phi)) / L, -s * 6 * (2 * xi - 1) / (L * L),
        s * (6 * xi - (2 - phi)) / L;
    return f;
}

// K = int E I Psi' Psi'^T + kappa G A (N' - Psi)(N' - Psi)^T dx, M = int rho A N N^T + rho I Psi Psi^T dx
// by 5-point Gauss-Legendre (exact: the integrands are polynomials of degree <= 6).
void planar_by_quadrature(double EI, double kGA, double rhoA, double rhoI, double L, Eigen::Matrix4d& K,
                          Eigen::Matrix4d& M) {
    const double phi = 12.0 * EI / (kGA * L * L);
    const double g[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
    const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                         0.2369268850561891};
    K.setZero();
    M.setZero();
    for (int q = 0; q < 5; ++q) {
        const PlanarShape f = planar_shape(0.5 * (g[q] + 1.0), L, phi);
        const double dx = 0.5 * L * w[q];
        const Eigen::Vector4d shear = f.dN - f.Psi;
        K += dx * (EI * f.dPsi * f.dPsi.transpose() + kGA * shear * shear.transpose());
        M += dx * (rhoA * f.N * f.N.transpose() + rhoI * f.Psi * f.Psi.transpose());
    }
}

Eigen::Matrix4d planar_block(const BeamMatrix& m, int v, int theta, double sign) {
    const int index[4] = {v, theta, v + 6, theta + 6};
    const double flip[4] = {1.0, sign, 1.0, sign};
    Eigen::Matrix4d block;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) block(i, j) = flip[i] * flip[j] * m(index[i], index[j]);
    return block;
}

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }
}  // namespace

TEST_CASE("circular sections: area, second moments, torsion constant and Cowper's shear coefficient") {
    const double d = 0.04;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    CHECK(s.area == Approx(PI * 0.02 * 0.02).epsilon(1e-14));
    CHECK(s.second_moment_y == Approx(PI * std::pow(0.02, 4) / 4.0).epsilon(1e-14));
    CHECK(s.second_moment_z == Approx(PI * std::pow(0.02, 4) / 4.0).epsilon(1e-14));
    CHECK(s.polar_moment == Approx(PI * std::pow(0.02, 4) / 2.0).epsilon(1e-14));
    CHECK(s.shear_modulus == Approx(210e9 / 2.6).epsilon(1e-14));
    CHECK(s.shear_coefficient_y == Approx(7.8 / 8.8).epsilon(1e-14));  // 6 (1.3) / (7 + 1.8)
    CHECK(s.shear_coefficient_z == s.shear_coefficient_y);

    const double D = 0.05, di = 0.03, m2 = 0.36;
    const BeamSection t = BeamSection::hollow_circle(D, di, E_steel, nu_steel, rho_steel);
    CHECK(t.area == Approx(PI * (D * D - di * di) / 4.0).epsilon(1e-14));
    CHECK(t.second_moment_y == Approx(PI * (std::pow(D, 4) - std::pow(di, 4)) / 64.0).epsilon(1e-14));
    CHECK(t.polar_moment == Approx(PI * (std::pow(D, 4) - std::pow(di, 4)) / 32.0).epsilon(1e-14));
    const double cowper_tube = 6.0 * 1.3 * (1 + m2) * (1 + m2) / (8.8 * (1 + m2) * (1 + m2) + 23.6 * m2);
    CHECK(t.shear_coefficient_y == Approx(cowper_tube).epsilon(1e-14));
}

TEST_CASE("element matrices equal the quadrature of the exact Timoshenko interpolation") {
    // A thick element (L/d = 2) so that phi ~ 0.5 and every shear term matters.
    const double d = 0.05, L = 0.1;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const BeamMatrix K = timoshenko_stiffness(s, L), M = timoshenko_mass(s, L);
    const double A = circle_area(d), I = circle_I(d), kGA = kappa_solid * G_steel * A;
    Eigen::Matrix4d Kq, Mq;
    planar_by_quadrature(E_steel * I, kGA, rho_steel * A, rho_steel * I, L, Kq, Mq);
    for (int plane = 0; plane < 2; ++plane) {
        // x-y: (u_y, theta_z) with theta_z = +du_y/dx; x-z: (u_z, theta_y) with theta_y = -du_z/dx.
        const int v = plane == 0 ? 1 : 2, theta = plane == 0 ? 5 : 4;
        const double sign = plane == 0 ? 1.0 : -1.0;
        CHECK((planar_block(K, v, theta, sign) - Kq).norm() <= 1e-12 * Kq.norm());
        CHECK((planar_block(M, v, theta, sign) - Mq).norm() <= 1e-12 * Mq.norm());
    }
    // Axial and torsion: linear bars.
    CHECK(K(0, 0) == Approx(E_steel * A / L).epsilon(1e-14));
    CHECK(K(0, 6) == Approx(-E_steel * A / L).epsilon(1e-14));
    CHECK(K(3, 3) == Approx(G_steel * 2.0 * I / L).epsilon(1e-14));
    CHECK(M(0, 6) == Approx(rho_steel * A * L / 6.0).epsilon(1e-14));
    CHECK(M(3, 9) == Approx(rho_steel * 2.0 * I * L / 6.0).epsilon(1e-14));
    // Axial, torsion and the two bending planes do not couple in a straight element.
    CHECK(K(0, 1) == 0.0);
    CHECK(K(3, 5) == 0.0);
    CHECK(K(1, 2) == 0.0);
    CHECK(M(1, 4) == 0.0);
    CHECK(M(2, 5) == 0.0);
}

TEST_CASE("element stiffness: symmetric, positive semi-definite, exactly the 6 rigid-body null modes") {
    const double d = 0.05, L = 0.2;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const BeamMatrix K = timoshenko_stiffness(s, L);
    CHECK((K - K.transpose()).norm() <= 1e-15 * K.norm());

    Eigen::SelfAdjointEigenSolver<BeamMatrix> eig(K);
    const double largest = eig.eigenvalues().maxCoeff();
    int zero = 0;
    for (int i = 0; i < 12; ++i) {
        CHECK(eig.eigenvalues()(i) > -1e-12 * largest);
        if (std::abs(eig.eigenvalues()(i)) < 1e-12 * largest) ++zero;
        else CHECK(eig.eigenvalues()(i) > 1e-8 * largest);
    }
    CHECK(zero == 6);

    // The rigid motions themselves (node 1 at x = 0, node 2 at x = L), right-handed:
    // a rotation a about z moves u_y = a x, about y moves u_z = -a x.
    std::vector<Eigen::Matrix<double, 12, 1>> rigid(6, Eigen::Matrix<double, 12, 1>::Zero());
    for (int t = 0; t < 3; ++t) rigid[t](t) = rigid[t](t + 6) = 1.0;
    rigid[3](3) = rigid[3](9) = 1.0;
    rigid[4](4) = rigid[4](10) = 1.0;
    rigid[4](8) = -L;
    rigid[5](5) = rigid[5](11) = 1.0;
    rigid[5](7) = L;
    for (const auto& r : rigid) CHECK((K * r).norm() <= 1e-12 * K.norm());
}

TEST_CASE("element mass: symmetric positive definite, the rigid-body mass and rotary inertia") {
    const double D = 0.06, di = 0.02, L = 0.15;
    const BeamSection s = BeamSection::hollow_circle(D, di, E_steel, nu_steel, rho_steel);
    const BeamMatrix M = timoshenko_mass(s, L);
    CHECK((M - M.transpose()).norm() <= 1e-15 * M.norm());
    Eigen::SelfAdjointEigenSolver<BeamMatrix> eig(M);
    CHECK(eig.eigenvalues().minCoeff() > 0.0);
    CHECK(Eigen::LLT<BeamMatrix>(M).info() == Eigen::Success);

    const double A = PI * (D * D - di * di) / 4.0, I = PI * (std::pow(D, 4) - std::pow(di, 4)) / 64.0, J = 2.0 * I;
    Eigen::Matrix<double, 12, 1> r;
    for (int t = 0; t < 3; ++t) {  // a translation carries the whole mass rho A L
        r.setZero();
        r(t) = r(t + 6) = 1.0;
        CHECK(r.dot(M * r) == Approx(rho_steel * A * L).epsilon(1e-13));
    }
    r.setZero();  // spin about the axis: rho J L (circle: J = polar moment of area)
    r(3) = r(9) = 1.0;
    CHECK(r.dot(M * r) == Approx(rho_steel * J * L).epsilon(1e-13));
    CHECK(M(3, 3) == Approx(rho_steel * J * L / 3.0).epsilon(1e-13));
    // Rigid rotation about z (or y) through node 1: the rod's rho A L^3 / 3 plus the sections' rho I L.
    r.setZero();
    r(5) = r(11) = 1.0;
    r(7) = L;
    CHECK(r.dot(M * r) == Approx(rho_steel * A * L * L * L / 3.0 + rho_steel * I * L).epsilon(1e-13));
    r.setZero();
    r(4) = r(10) = 1.0;
    r(8) = -L;
    CHECK(r.dot(M * r) == Approx(rho_steel * A * L * L * L / 3.0 + rho_steel * I * L).epsilon(1e-13));
}

TEST_CASE("cantilever with a tip load: P L^3 / (3 E I) + P L / (kappa G A), exact with one element") {
    const double d = 0.05, L = 0.2, P = 1000.0;  // L/d = 4: the shear term is ~5 % of the deflection
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const double A = circle_area(d), I = circle_I(d);
    const double expected = P * L * L * L / (3.0 * E_steel * I) + P * L / (kappa_solid * G_steel * A);
    const double tip_rotation = P * L * L / (2.0 * E_steel * I);  // the section rotation: no shear part
    for (int n : {1, 5}) {
        const UniformShaft shaft(s, L, n);
        Eigen::VectorXd f = Eigen::VectorXd::Zero(shaft.dof_count());
        f(shaft_dof(n, ShaftDof::lateral_y)) = P;
        f(shaft_dof(n, ShaftDof::lateral_z)) = P;
        const Eigen::VectorXd u = solve_static(shaft, clamped_at_node_zero(), f);
        CHECK(relative(u(shaft_dof(n, ShaftDof::lateral_y)), expected) < 1e-9);
        CHECK(relative(u(shaft_dof(n, ShaftDof::lateral_z)), expected) < 1e-9);
        CHECK(relative(u(shaft_dof(n, ShaftDof::rotation_z)), tip_rotation) < 1e-9);   // +: theta_z follows u_y
        CHECK(relative(u(shaft_dof(n, ShaftDof::rotation_y)), -tip_rotation) < 1e-9);  // -: theta_y opposes u_z
    }
}

TEST_CASE("simply supported with a central load: P L^3 / (48 E I) + P L / (4 kappa G A)") {
    const double d = 0.04, L = 0.24, P = 2000.0;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const double expected =
        P * L * L * L / (48.0 * E_steel * circle_I(d)) + P * L / (4.0 * kappa_solid * G_steel * circle_area(d));
    for (int n : {2, 8}) {
        const UniformShaft shaft(s, L, n);
        const std::vector<int> fixed = {shaft_dof(0, ShaftDof::axial),     shaft_dof(0, ShaftDof::lateral_y),
                                        shaft_dof(0, ShaftDof::lateral_z), shaft_dof(0, ShaftDof::torsion),
                                        shaft_dof(n, ShaftDof::lateral_y), shaft_dof(n, ShaftDof::lateral_z)};
        Eigen::VectorXd f = Eigen::VectorXd::Zero(shaft.dof_count());
        f(shaft_dof(n / 2, ShaftDof::lateral_y)) = P;
        const Eigen::VectorXd u = solve_static(shaft, fixed, f);
        CHECK(relative(u(shaft_dof(n / 2, ShaftDof::lateral_y)), expected) < 1e-9);
        CHECK(std::abs(u(shaft_dof(n / 2, ShaftDof::lateral_z))) < 1e-12 * expected);
    }
}

TEST_CASE("tip torque T L / (G J) and axial load P L / (E A)") {
    const double D = 0.05, di = 0.035, L = 0.6, T = 300.0, P = 5e4;
    const BeamSection s = BeamSection::hollow_circle(D, di, E_steel, nu_steel, rho_steel);
    const double A = PI * (D * D - di * di) / 4.0, J = PI * (std::pow(D, 4) - std::pow(di, 4)) / 32.0;
    const UniformShaft shaft(s, L, 3);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(shaft.dof_count());
    f(shaft_dof(3, ShaftDof::torsion)) = T;
    f(shaft_dof(3, ShaftDof::axial)) = P;
    const Eigen::VectorXd u = solve_static(shaft, clamped_at_node_zero(), f);
    CHECK(relative(u(shaft_dof(3, ShaftDof::torsion)), T * L / (G_steel * J)) < 1e-12);
    CHECK(relative(u(shaft_dof(3, ShaftDof::axial)), P * L / (E_steel * A)) < 1e-12);
    CHECK(relative(u(shaft_dof(1, ShaftDof::torsion)), T * L / 3.0 / (G_steel * J)) < 1e-12);
}

TEST_CASE("bearing springs: a tip spring in parallel with the cantilever's own flexibility") {
    const double d = 0.03, L = 0.3, P = 500.0, k_bearing = 2e6;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const double compliance = L * L * L / (3.0 * E_steel * circle_I(d)) + L / (kappa_solid * G_steel * circle_area(d));
    UniformShaft shaft(s, L, 4);
    shaft.add_support(4, 0.0, k_bearing, 0.0, 0.0, 0.0, 0.0);
    shaft.add_support(4, 0.0, k_bearing, 0.0, 0.0, 0.0, 0.0);  // supports at one node add up
    Eigen::VectorXd f = Eigen::VectorXd::Zero(shaft.dof_count());
    f(shaft_dof(4, ShaftDof::lateral_y)) = P;
    f(shaft_dof(4, ShaftDof::lateral_z)) = P;
    const Eigen::VectorXd u = solve_static(shaft, clamped_at_node_zero(), f);
    CHECK(relative(u(shaft_dof(4, ShaftDof::lateral_y)), P / (2.0 * k_bearing + 1.0 / compliance)) < 1e-9);
    CHECK(relative(u(shaft_dof(4, ShaftDof::lateral_z)), P * compliance) < 1e-9);

    // A shaft on two stiff-but-finite bearings, every direction: no zero modes left.
    UniformShaft supported(s, L, 6);
    supported.add_support(0, 1e8, 1e8, 1e8, 1e3, 0.0, 0.0);
    supported.add_support(6, 0.0, 1e8, 1e8, 0.0, 0.0, 0.0);
    CHECK(frequencies_hz(supported, {})(0) > 1.0);
}

TEST_CASE("assembly: sparse and dense agree with element blocks summed at shared nodes") {
    const BeamSection s = BeamSection::solid_circle(0.02, E_steel, nu_steel, rho_steel);
    const UniformShaft shaft(s, 0.9, 3);
    CHECK(shaft.node_count() == 4);
    CHECK(shaft.dof_count() == 24);
    CHECK(shaft.element_length() == Approx(0.3).epsilon(1e-15));
    CHECK(shaft.node_position(2) == Approx(0.6).epsilon(1e-15));
    const BeamMatrix ke = timoshenko_stiffness(s, 0.3), me = timoshenko_mass(s, 0.3);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(24, 24), M = Eigen::MatrixXd::Zero(24, 24);
    for (int e = 0; e < 3; ++e) {
        K.block<12, 12>(6 * e, 6 * e) += ke;
        M.block<12, 12>(6 * e, 6 * e) += me;
    }
    CHECK((Eigen::MatrixXd(shaft.stiffness_sparse()) - K).norm() <= 1e-14 * K.norm());
    CHECK((Eigen::MatrixXd(shaft.mass_sparse()) - M).norm() <= 1e-14 * M.norm());
    CHECK((shaft.stiffness() - K).norm() <= 1e-14 * K.norm());
    CHECK((shaft.mass() - M).norm() <= 1e-14 * M.norm());

    const std::vector<int> fixed = {23, 0, 5, 0};  // any order, duplicates allowed
    const Eigen::MatrixXd reduced = remove_dofs(K, fixed);
    REQUIRE(reduced.rows() == 21);
    CHECK(reduced(0, 0) == K(1, 1));
    CHECK(reduced(3, 4) == K(4, 6));
    CHECK(reduced(20, 20) == K(22, 22));
    CHECK((Eigen::MatrixXd(remove_dofs(shaft.stiffness_sparse(), fixed)) - reduced).norm() == 0.0);
}

TEST_CASE("simply supported slender shaft converges to the bending frequencies") {
    // L/d = 200: the Timoshenko frequencies lie within 3e-5 n^2 of Euler-Bernoulli's.
    const double d = 0.005, L = 1.0;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    double previous_error[3] = {0, 0, 0};
    for (int n : {4, 8, 16, 32}) {
        const UniformShaft shaft(s, L, n);
        const Eigen::VectorXd f = frequencies_hz(shaft, simply_supported_xy(shaft));
        for (int mode = 1; mode <= 3; ++mode) {
            const double error = relative(f(mode - 1), timoshenko_ss_hz(mode, L, d));
            CHECK(f(mode - 1) >= timoshenko_ss_hz(mode, L, d) * (1.0 - 1e-12));  // consistent mass: from above
            if (n >= 8 && n <= 16) CHECK(std::log2(previous_error[mode - 1] / error) > 3.8);  // O(h^4)
            previous_error[mode - 1] = error;
            if (n == 32) {
                CHECK(error < 1e-5);  // measured 8.3e-8, 1.3e-6, 6.7e-6
                CHECK(relative(f(mode - 1), euler_bernoulli_ss_hz(mode, L, d)) < 3e-4);
            }
        }
    }
}

TEST_CASE("free-free slender shaft: first bending at beta L = 4.7300407, and 6 rigid-body modes in 3D") {
    const double d = 0.005, L = 1.0;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const UniformShaft shaft(s, L, 32);
    const double bl = 4.7300407;
    const double expected =
        bl * bl / (2.0 * PI * L * L) * std::sqrt(E_steel * circle_I(d) / (rho_steel * circle_area(d)));
    const Eigen::VectorXd f = frequencies_hz(shaft, {});
    for (int i = 0; i < 6; ++i) CHECK(f(i) < 1e-4 * expected);
    CHECK(relative(f(6), expected) < 2e-4);  // the Timoshenko correction at L/d = 200, ~7e-5
    CHECK(relative(f(7), expected) < 2e-4);  // the same in the other plane
    const Eigen::VectorXd planar = frequencies_hz(shaft, all_but(shaft, {ShaftDof::lateral_z, ShaftDof::rotation_y}));
    CHECK(planar(0) < 1e-4 * expected);
    CHECK(planar(1) < 1e-4 * expected);
    CHECK(relative(planar(2), f(6)) < 1e-9);
}

TEST_CASE("fixed-free torsion: f_n = (2n - 1) / (4 L) sqrt(G / rho)") {
    const double d = 0.03, L = 0.5;
    const int n = 32;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const UniformShaft shaft(s, L, n);
    std::vector<int> fixed = all_but(shaft, {ShaftDof::torsion});
    fixed.push_back(shaft_dof(0, ShaftDof::torsion));
    const Eigen::VectorXd f = frequencies_hz(shaft, fixed);
    for (int mode = 1; mode <= 3; ++mode) {
        const double expected = (2 * mode - 1) / (4.0 * L) * std::sqrt(G_steel / rho_steel);
        // Linear elements with consistent mass: relative error ~ (k h)^2 / 24, k the wave number.
        const double kh = (2 * mode - 1) * PI / (2.0 * L) * (L / n);
        CHECK(f(mode - 1) > expected);
        CHECK(relative(f(mode - 1), expected) < kh * kh / 20.0);
    }
}

TEST_CASE("thick simply supported shaft (L/d = 5) converges to the Timoshenko frequency equation") {
    // The element's shear strain is constant per element, so where shear carries a good part of the
    // strain energy the frequencies converge as O(h^2); Richardson's (4 f_h - f_2h) / 3 extrapolation of
    // 16 and 32 elements must then land on the closed form far more closely than either mesh.
    const double d = 0.04, L = 0.2;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    const UniformShaft coarse(s, L, 16), shaft(s, L, 32);
    const Eigen::VectorXd f16 = frequencies_hz(coarse, simply_supported_xy(coarse));
    const Eigen::VectorXd f = frequencies_hz(shaft, simply_supported_xy(shaft));
    std::vector<int> xz = all_but(shaft, {ShaftDof::lateral_z, ShaftDof::rotation_y});
    xz.push_back(shaft_dof(0, ShaftDof::lateral_z));
    xz.push_back(shaft_dof(32, ShaftDof::lateral_z));
    const Eigen::VectorXd g = frequencies_hz(shaft, xz);
    const double tolerance_32[4] = {5e-5, 5e-4, 2e-3, 4e-3};  // measured 2.6e-5, 3.3e-4, 1.2e-3, 3.0e-3
    for (int mode = 1; mode <= 4; ++mode) {
        const double expected = timoshenko_ss_hz(mode, L, d);
        const double error = relative(f(mode - 1), expected);
        CHECK(f(mode - 1) > expected);
        CHECK(error < tolerance_32[mode - 1]);
        CHECK(std::log2(relative(f16(mode - 1), expected) / error) > 1.9);
        const double extrapolated = (4.0 * f(mode - 1) - f16(mode - 1)) / 3.0;
        CHECK(relative(extrapolated, expected) < 0.05 * error);
        CHECK(relative(g(mode - 1), f(mode - 1)) < 1e-10);  // both planes, both sign conventions
        // Shear and rotary inertia matter here: well below Euler-Bernoulli.
        CHECK(f(mode - 1) < euler_bernoulli_ss_hz(mode, L, d) * (1.0 - 0.02 * mode));
    }
}

TEST_CASE("bad input throws naming the parameter") {
    CHECK_THROWS_WITH(BeamSection::solid_circle(0.0, E_steel, nu_steel, rho_steel), Contains("outer diameter"));
    CHECK_THROWS_WITH(BeamSection::solid_circle(0.02, -1.0, nu_steel, rho_steel), Contains("youngs_modulus"));
    CHECK_THROWS_WITH(BeamSection::solid_circle(0.02, E_steel, 0.5, rho_steel), Contains("poisson_ratio"));
    CHECK_THROWS_WITH(BeamSection::solid_circle(0.02, E_steel, -0.1, rho_steel), Contains("poisson_ratio"));
    CHECK_THROWS_WITH(BeamSection::solid_circle(0.02, E_steel, nu_steel, 0.0), Contains("density"));
    CHECK_THROWS_WITH(BeamSection::hollow_circle(0.02, 0.02, E_steel, nu_steel, rho_steel), Contains("inner diameter"));
    CHECK_THROWS_WITH(BeamSection::hollow_circle(0.02, -0.01, E_steel, nu_steel, rho_steel),
                      Contains("inner diameter"));

    const BeamSection good = BeamSection::solid_circle(0.02, E_steel, nu_steel, rho_steel);
    BeamSection bad = good;
    bad.shear_modulus = 0.0;
    CHECK_THROWS_WITH(timoshenko_stiffness(bad, 0.1), Contains("shear_modulus"));
    bad = good;
    bad.shear_coefficient_z = std::nan("");
    CHECK_THROWS_WITH(timoshenko_mass(bad, 0.1), Contains("shear_coefficient_z"));
    bad = good;
    bad.second_moment_y = -1.0;
    CHECK_THROWS_WITH(bad.validate(), Contains("second_moment_y"));
    CHECK_THROWS_WITH(timoshenko_stiffness(good, 0.0), Contains("element length"));
    CHECK_THROWS_WITH(timoshenko_mass(good, -0.1), Contains("element length"));

    CHECK_THROWS_WITH(UniformShaft(good, 0.0, 4), Contains("shaft length"));
    CHECK_THROWS_WITH(UniformShaft(good, 1.0, 0), Contains("element_count"));
    UniformShaft shaft(good, 1.0, 4);
    CHECK_THROWS_WITH(shaft.add_support(5, 1, 1, 1, 1, 1, 1), Contains("support node"));
    CHECK_THROWS_WITH(shaft.add_support(0, 1, -1, 1, 1, 1, 1), Contains("support ky"));
    CHECK_THROWS_WITH(remove_dofs(shaft.stiffness(), {30}), Contains("fixed DOF"));
}

// Not run by default: `test_timoshenko_beam "[.table]"` prints the convergence table of docs/shaft.md.
TEST_CASE("convergence table", "[.table]") {
    const double d = 0.005, L = 1.0;
    const BeamSection s = BeamSection::solid_circle(d, E_steel, nu_steel, rho_steel);
    std::printf("simply supported, L/d = 200: relative error vs Timoshenko exact (vs Euler-Bernoulli)\n");
    double previous[3] = {0, 0, 0};
    for (int n : {4, 8, 16, 32}) {
        const UniformShaft shaft(s, L, n);
        const Eigen::VectorXd f = frequencies_hz(shaft, simply_supported_xy(shaft));
        std::printf("%3d elements:", n);
        for (int mode = 1; mode <= 3; ++mode) {
            const double error = relative(f(mode - 1), timoshenko_ss_hz(mode, L, d));
            std::printf("  mode %d %.3e (%.3e)", mode, error, relative(f(mode - 1), euler_bernoulli_ss_hz(mode, L, d)));
            if (previous[mode - 1] > 0) std::printf(" order %.2f", std::log2(previous[mode - 1] / error));
            previous[mode - 1] = error;
        }
        std::printf("\n");
    }
    const double dt = 0.04, Lt = 0.2;
    const BeamSection thick = BeamSection::solid_circle(dt, E_steel, nu_steel, rho_steel);
    std::printf("simply supported, L/d = 5: relative error vs Timoshenko exact; Timoshenko / Euler-Bernoulli\n");
    for (int n : {8, 16, 32}) {
        const UniformShaft shaft(thick, Lt, n);
        const Eigen::VectorXd f = frequencies_hz(shaft, simply_supported_xy(shaft));
        std::printf("%3d elements:", n);
        for (int mode = 1; mode <= 4; ++mode)
            std::printf("  mode %d %.3e", mode, relative(f(mode - 1), timoshenko_ss_hz(mode, Lt, dt)));
        std::printf("\n");
    }
    {
        const UniformShaft a(thick, Lt, 16), b(thick, Lt, 32);
        const Eigen::VectorXd fa = frequencies_hz(a, simply_supported_xy(a)),
                              fb = frequencies_hz(b, simply_supported_xy(b));
        std::printf("Richardson 16/32:");
        for (int mode = 1; mode <= 4; ++mode)
            std::printf("  mode %d %.3e", mode,
                        relative((4 * fb(mode - 1) - fa(mode - 1)) / 3, timoshenko_ss_hz(mode, Lt, dt)));
        std::printf("\n");
    }
    for (int mode = 1; mode <= 4; ++mode)
        std::printf("  mode %d: Timoshenko %.2f Hz, Euler-Bernoulli %.2f Hz\n", mode, timoshenko_ss_hz(mode, Lt, dt),
                    euler_bernoulli_ss_hz(mode, Lt, dt));
    const UniformShaft ff(s, L, 32);
    const double bl = 4.7300407;
    const double eb = bl * bl / (2.0 * PI * L * L) * std::sqrt(E_steel * circle_I(d) / (rho_steel * circle_area(d)));
    std::printf("free-free 32 elements: f1 %.6f Hz, beta L closed form %.6f Hz, rel %.3e\n", frequencies_hz(ff, {})(6),
                eb, relative(frequencies_hz(ff, {})(6), eb));
    const UniformShaft tor(thick, 0.5, 32);
    std::vector<int> fixed = all_but(tor, {ShaftDof::torsion});
    fixed.push_back(0 * 6 + 3);
    const Eigen::VectorXd ft = frequencies_hz(tor, fixed);
    for (int mode = 1; mode <= 3; ++mode) {
        const double ex = (2 * mode - 1) / (4.0 * 0.5) * std::sqrt(G_steel / rho_steel);
        std::printf("torsion fixed-free 32 elements mode %d: %.3e\n", mode, relative(ft(mode - 1), ex));
    }
}
