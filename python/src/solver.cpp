// Bindings for include/camfollower/solver: run any bound system, get its recording as NumPy views.
// One templated binder (bind_simulate<System>) serves every system type.
#include "run.hpp"

namespace camfollower::python {


template <class System>
void bind_run(py::module_& m) {
    m.def(
        "_run",
        [](const System& system, double duration, double time_step, std::size_t decimation, std::optional<double> gamma,
           std::optional<double> beta, double hht_alpha, const std::string& linear_solver, double residual_tolerance,
           double increment_tolerance, int max_iterations, int max_halvings, double record_from,
           double max_output_bytes, const py::object& progress, double progress_interval) {
            const NewmarkSettings s = settings_from(time_step, gamma, beta, hht_alpha, linear_solver, residual_tolerance,
                                                    increment_tolerance, max_iterations, max_halvings);
            return run_system(system, duration, s, decimation, record_from, max_output_bytes, progress,
                              progress_interval);
        },
        py::arg("system"), py::arg("duration"), py::arg("time_step"), py::arg("decimation"), py::arg("gamma"),
        py::arg("beta"), py::arg("hht_alpha"), py::arg("linear_solver"), py::arg("residual_tolerance"),
        py::arg("increment_tolerance"), py::arg("max_iterations"), py::arg("max_halvings"), py::arg("record_from"),
        py::arg("max_output_bytes"), py::arg("progress"), py::arg("progress_interval"),
        "Internal: camfollower.simulate() calls this and wraps the output in a Result.");
}

void bind_solver(py::module_& m) { bind_run<CamFollowerModel>(m); }

}  // namespace camfollower::python
