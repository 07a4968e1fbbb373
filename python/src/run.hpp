// SPDX-License-Identifier: BSD-3-Clause
// Shared by the binding files: Newmark settings from keyword arguments, and one templated runner
// that integrates any system with the GIL released, honours Ctrl-C and hands back NumPy views.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/model/cam_follower_model.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/solver/simulate.hpp"

namespace camfollower::python {

inline NewmarkSettings settings_from(double time_step, std::optional<double> gamma, std::optional<double> beta, double hht_alpha,
                              const std::string& linear_solver, double residual_tolerance, double increment_tolerance,
                              int max_iterations, int max_halvings) {
    // gamma and beta default to the average-acceleration rule, or to HHT's own values.
    NewmarkSettings s = NewmarkSettings::hht(hht_alpha, time_step);
    if (gamma) s.gamma = *gamma;
    if (beta) s.beta = *beta;
    s.residual_tolerance = residual_tolerance;
    s.increment_tolerance = increment_tolerance;
    s.max_iterations = max_iterations;
    s.max_halvings = max_halvings;
    set_linear_solver(s, linear_solver);
    s.validate();
    return s;
}

// Contact-loss intervals per contact, {name: [(start, end), ...]}, for systems that track them.
inline py::dict losses_of(const CamFollowerModel&, const State<CamFollowerModel>& s) {
    py::list out;
    for (const auto& [a, b] : CamFollowerModel::contact_loss(s.workspace, s.t)) out.append(py::make_tuple(a, b));
    py::dict d;
    d["cam"] = out;
    return d;
}
template <int N>
py::dict losses_of(const Mechanism<N>& m, const State<Mechanism<N>>& s) {
    py::dict d;
    for (std::size_t i = 0; i < m.contacts().size(); ++i) {
        py::list out;
        for (const auto& [a, b] : Mechanism<N>::contact_loss(s.workspace, i, s.t)) out.append(py::make_tuple(a, b));
        d[py::str(m.contacts()[i].name())] = out;
    }
    return d;
}

// The raw output handed to camfollower.results.Result: channel names, DOF names, a channels x rows
// view on the C++ buffer (kept alive by the view's base), statistics.
template <class System>
py::dict run_system(const System& system, double duration, const NewmarkSettings& settings, std::size_t decimation,
                    double record_from, double max_output_bytes, const py::object& progress,
                    double progress_interval, const SettleOptions& settle) {
    RunOptions options;
    options.settle = settle;
    options.duration = duration;
    options.record.decimation = decimation;
    options.record.from_time = record_from;
    options.record.max_bytes = max_output_bytes;
    detail::require_positive(progress_interval, "progress_interval", "(s)");
    // Every few thousand steps: after progress_interval seconds take the GIL, honour Ctrl-C (a pending
    // KeyboardInterrupt cancels the run) and call the progress callback.
    std::optional<py::error_already_set> python_error;
    auto last = std::chrono::steady_clock::now();
    options.progress_every = 2048;
    options.progress = [&](std::uint64_t done, std::uint64_t planned) {
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last).count() < progress_interval) return true;
        last = now;
        py::gil_scoped_acquire acquire;
        try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!progress.is_none()) {
                const py::object keep_going = progress(done, planned);
                if (!keep_going.is_none() && !keep_going.cast<bool>()) return false;
            }
        } catch (py::error_already_set& e) {
            python_error.emplace(std::move(e));
            return false;
        }
        return true;
    };
    auto result = std::make_shared<RunResult<System>>();
    {
        py::gil_scoped_release release;
        *result = simulate(system, settings, options);
    }
    if (python_error) throw std::move(*python_error);
    const Recording& rec = result->recording;
    auto* keep = new std::shared_ptr<RunResult<System>>(result);
    py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<RunResult<System>>*>(p); });
    const auto channels = static_cast<py::ssize_t>(rec.names.size());
    const auto rows = static_cast<py::ssize_t>(rec.rows);
    const auto stride = static_cast<py::ssize_t>(sizeof(double));
    py::array_t<double> data({channels, rows}, {stride * static_cast<py::ssize_t>(rec.capacity), stride},
                             rec.data.data(), base);
    py::dict d;
    d["names"] = rec.names;
    d["dofs"] = rec.dofs;
    d["data"] = data;
    const SolverStatistics& st = result->report.stats;
    py::dict stats;
    stats["steps"] = st.steps;
    stats["newton_iterations"] = st.newton_iterations;
    stats["mean_iterations"] = st.mean_iterations();
    stats["max_iterations_in_a_step"] = st.max_iterations_in_a_step;
    stats["halvings"] = st.halvings;
    stats["time_step"] = result->time_step;
    stats["decimation"] = result->decimation;
    stats["cancelled"] = result->report.cancelled;
    stats["backend"] = result->backend;
    const SettleReport& sr = result->settle;
    if (sr.requested) {
        py::dict st;
        st["settled"] = sr.settled;
        st["revolutions"] = sr.revolutions;
        st["change"] = sr.change;
        st["change_absolute"] = sr.change_absolute;
        st["tolerance"] = settle.tolerance;
        st["history"] = sr.history;
        stats["settle"] = st;
    }
    d["stats"] = stats;
    d["contact_loss"] = losses_of(system, result->final_state);
    d["final_time"] = result->final_state.t;
    return d;
}


// Binds _run(system, ...) for one system type: camfollower.simulate() calls it and wraps the output in
// a Result. `run` is run_system or a dispatcher over several system types.
template <class System, class Run>
void bind_run(py::module_& m, Run run) {
    m.def(
        "_run",
        [run](const System& system, double duration, double time_step, std::size_t decimation,
              std::optional<double> gamma, std::optional<double> beta, double hht_alpha,
              const std::string& linear_solver, double residual_tolerance, double increment_tolerance,
              int max_iterations, int max_halvings, double record_from, double max_output_bytes,
              const py::object& progress, double progress_interval, std::optional<double> settle_period,
              const std::vector<int>& settle_dofs, double settle_tolerance, int settle_min_revolutions,
              int settle_max_revolutions) {
            const NewmarkSettings s = settings_from(time_step, gamma, beta, hht_alpha, linear_solver, residual_tolerance,
                                                    increment_tolerance, max_iterations, max_halvings);
            SettleOptions settle;
            if (settle_period) {
                settle.enabled = true;
                settle.period = *settle_period;
                settle.dofs = settle_dofs;
                settle.tolerance = settle_tolerance;
                settle.min_revolutions = settle_min_revolutions;
                settle.max_revolutions = settle_max_revolutions;
            }
            return run(system, duration, s, decimation, record_from, max_output_bytes, progress, progress_interval, settle);
        },
        py::arg("system"), py::arg("duration"), py::arg("time_step"), py::arg("decimation"), py::arg("gamma"),
        py::arg("beta"), py::arg("hht_alpha"), py::arg("linear_solver"), py::arg("residual_tolerance"),
        py::arg("increment_tolerance"), py::arg("max_iterations"), py::arg("max_halvings"), py::arg("record_from"),
        py::arg("max_output_bytes"), py::arg("progress"), py::arg("progress_interval"), py::arg("settle_period") = py::none(),
        py::arg("settle_dofs") = std::vector<int>{}, py::arg("settle_tolerance") = 1e-4,
        py::arg("settle_min_revolutions") = 2, py::arg("settle_max_revolutions") = 200,
        "Internal: camfollower.simulate() calls this and wraps the output in a Result.");
}

}  // namespace camfollower::python
