// A linear N-DOF test system in the solver's System concept: M q'' + C q' + K q = F(t), no contact.
#pragma once

#include <functional>

#include <Eigen/Core>

#include "camfollower/contact/hertz.hpp"

template <int N>
struct LinearSystem {
    static constexpr int dofs = N;
    using Vector = Eigen::Matrix<double, N, 1>;
    using Matrix = Eigen::Matrix<double, N, N>;

    Matrix M = Matrix::Identity(), C = Matrix::Zero(), K = Matrix::Identity();
    Vector q0 = Vector::Zero();
    std::function<Vector(double)> load = [](double) { return Vector::Zero(); };

    struct TimeContext {
        double t, theta;
        Vector g, external;
        double pressure_angle() const { return 0.0; }
    };
    struct Nonlinear {
        Vector force;
        double delta;
        camfollower::ContactResponse contact;
    };

    const Matrix& mass_matrix() const { return M; }
    const Matrix& damping_matrix() const { return C; }
    const Matrix& stiffness_matrix() const { return K; }
    const Vector& initial_state() const { return q0; }
    TimeContext at_time(double t) const { return {t, 0.0, Vector::Zero(), load(t)}; }
    Nonlinear nonlinear(const TimeContext& c, const Vector&, const Vector&) const {
        return {-c.external, 0.0, {0.0, 0.0, 0.0, true}};
    }
    Vector tangent_row(const TimeContext&, const Nonlinear&, double) const { return Vector::Zero(); }
};
