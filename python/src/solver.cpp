// SPDX-License-Identifier: BSD-3-Clause
// Bindings for include/camfollower/solver: run the original 7-DOF model (mechanisms: mechanism.cpp),
// get its recording as NumPy views.
#include "run.hpp"

namespace camfollower::python {

void bind_solver(py::module_& m) {
    bind_run<CamFollowerModel>(m, [](const CamFollowerModel& system, auto&&... args) {
        return run_system(system, args...);
    });
    bind_shoot<CamFollowerModel>(m, [](const CamFollowerModel& system, auto&&... args) { return shoot_system(system, args...); });
}

}  // namespace camfollower::python
