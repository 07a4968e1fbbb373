// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/solver: run the original 7-DOF model (mechanisms: mechanism.cpp),
// get its recording as NumPy views.
#include "run.hpp"

namespace camfollower::python {

void bind_solver(py::module_& m) {
    // The integration methods from the one table (solver/settings.hpp): name -> (order, summary).
    py::dict methods;
    for (const MethodTraits& t : method_table) methods[py::str(t.name)] = py::make_tuple(t.order, t.summary);
    m.attr("METHODS") = methods;
    m.attr("RUNGE_KUTTA_DEFAULT_TOLERANCE") = runge_kutta_default_tolerance;
    bind_run<CamFollowerModel>(m, [](const CamFollowerModel& system, auto&&... args) {
        return run_system(system, args...);
    });
    bind_shoot<CamFollowerModel>(m, [](const CamFollowerModel& system, auto&&... args) { return shoot_system(system, args...); });
}

}  // namespace camfollower::python
