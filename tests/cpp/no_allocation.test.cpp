// SPDX-License-Identifier: BSD-3-Clause
// No heap allocation per time step, for dynamic-size models too: the steppers run hundreds of steps
// with Eigen's allocations forbidden (EIGEN_RUNTIME_NO_MALLOC). The system is local to this file, so
// its steppers are compiled here only, with the check.
#include <stdexcept>
#define EIGEN_RUNTIME_NO_MALLOC
// A failed Eigen assertion (a forbidden allocation among them) throws here instead of aborting.
#define eigen_assert(x)                                                    \
    do {                                                                   \
        if (!(x)) throw std::runtime_error("Eigen assertion failed: " #x); \
    } while (false)

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <Eigen/Core>

#include "camfollower/solver/dispatch.hpp"
#include "camfollower/solver/settings.hpp"

using namespace camfollower;

namespace {

// Two masses on a soft spring, coupled by a stiff, damped one, driven on the first: dynamic-size
// vectors and matrices, the load written in place.
struct DynamicCoupled {
    using Vector = Eigen::VectorXd;
    using Matrix = Eigen::MatrixXd;
    Matrix M = Matrix::Identity(2, 2), C{2, 2}, K{2, 2};
    DynamicCoupled() {
        C << 1e3, -1e3, -1e3, 1e3;
        K << 250.0 + 1e8, -1e8, -1e8, 1e8;
    }
    int size() const { return 2; }
    const Matrix& mass() const { return M; }
    const Matrix& damping() const { return C; }
    const Matrix& stiffness() const { return K; }
    void load(double t, Vector& p) const { p[0] = std::sin(6.0 * t), p[1] = 0.0; }
    Vector initial_displacement() const { return Vector::Zero(2); }
};

template <class Stepper>
void run_without_allocation(const char* method, bool under_tolerance = true) {
    const DynamicCoupled system;
    SolverSettings s;
    s.method = method_from_name(method);
    s.time_step = 1e-3;
    if (under_tolerance) s.tolerance = 1e-7;
    s.max_halvings = 12;  // Newmark under a tolerance: steps down to time_step / 4096
    Stepper stepper(system, s);
    State<DynamicCoupled> state = stepper.start(0.0, system.initial_displacement(), Eigen::VectorXd::Zero(2));
    SolverStatistics stats;
    for (int i = 0; i < 10; ++i) stepper.step(state, stats);  // the start: first step size, first factorization
    const std::uint64_t before = stats.steps;
    Eigen::internal::set_is_malloc_allowed(false);
    std::string failure;
    try {
        for (int i = 0; i < 300; ++i) stepper.step(state, stats);
    } catch (const std::exception& e) {
        failure = e.what();
    }
    Eigen::internal::set_is_malloc_allowed(true);
    INFO(method << ": " << stats.steps - before << " steps to t = " << state.t << " s, " << stats.rejected_steps
                << " rejected");
    CHECK(failure.empty());
    CHECK(stats.steps - before >= 50u);
    CHECK(state.q.allFinite());
}

}  // namespace

TEST_CASE("The allocation check is live: a dynamic-size vector made with allocations forbidden throws") {
    Eigen::internal::set_is_malloc_allowed(false);
    bool thrown = false;
    try {
        Eigen::VectorXd x(5);
        x.setZero();
    } catch (const std::runtime_error&) {
        thrown = true;
    }
    Eigen::internal::set_is_malloc_allowed(true);
    CHECK(thrown);
}

// Every method of method_table, on the stepper the dispatcher gives it; the Newmark family also at fixed
// steps, every method that takes one under a tolerance.
TEST_CASE("Every method steps a dynamic-size model without heap allocation") {
    const DynamicCoupled system;
    for (const MethodTraits& t : method_table) {
        if (t.stepper == StepperKind::automatic) continue;
        SolverSettings s;
        s.method = t.method;
        with_stepper(system, s, [&](auto tag) {
            using Stepper = typename decltype(tag)::type;
            if (t.method != Method::hht) run_without_allocation<Stepper>(t.name);
            // (Fox-Goodwin's fixed 1 ms step is beyond its stability limit on this model.)
            if (is_newmark_family(t.method) && t.method != Method::fox_goodwin)
                run_without_allocation<Stepper>(t.name, false);
        });
    }
}
