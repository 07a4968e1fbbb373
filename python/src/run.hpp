// SPDX-License-Identifier: BSD-3-Clause
// Shared by the binding files: Newmark settings from keyword arguments, and one templated runner
// that integrates any system with the GIL released, honours Ctrl-C and hands back NumPy views.
#pragma once

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <memory>
#include <optional>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/solver/simulate.hpp"
#include "camfollower/solver/simulate_many.hpp"
#include "camfollower/precompiled.hpp"  // the mechanisms and simulate() for them, compiled once

namespace camfollower::python {

// The settings as a run uses them: a Runge-Kutta method without a tolerance runs under
// runge_kutta_default_tolerance (the front ends' rule; SolverSettings keeps what was asked).
inline SolverSettings as_run(SolverSettings s) {
    give_default_tolerance(s);
    s.validate();
    return s;
}

// Contact-loss intervals per contact, (name, [(start, end), ...]), for systems that track them.
using ContactLosses = std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>>;
template <int N>
ContactLosses losses_of(const Mechanism<N>& m, const State<Mechanism<N>>& s) {
    ContactLosses out;
    for (std::size_t i = 0; i < m.contacts().size(); ++i)
        out.emplace_back(m.contacts()[i].name(), Mechanism<N>::contact_loss(s.workspace, i, s.t));
    return out;
}

// What Python gets from a run, whatever the system's type: filled without the GIL, turned into a dict
// with it (dict_of).
struct RunOutput {
    Recording recording;
    IntegrationReport report;
    double time_step = 0.0;
    std::size_t decimation = 1;
    SettleReport settle_report;
    const char* backend = "";
    const char* method = "";
    const char* requested_method = "";
    std::string method_choice;
    std::string velocity_choice;
    double highest_mode_hz = 0.0;
    double final_time = 0.0;
    ContactLosses losses;
    // Located contact losses and re-contacts: (time, switching function's name, +1 made / -1 lost).
    std::vector<std::tuple<double, std::string, int>> events;
    SettleOptions settle;
};

template <class System>
std::shared_ptr<RunOutput> output_of(const System& system, RunResult<System>&& r, const SettleOptions& settle) {
    auto out = std::make_shared<RunOutput>();
    out->recording = std::move(r.recording);
    out->report = r.report;
    out->time_step = r.time_step;
    out->decimation = r.decimation;
    out->settle_report = std::move(r.settle);
    out->backend = r.backend;
    out->method = r.method;
    out->requested_method = r.requested_method;
    out->method_choice = std::move(r.method_choice);
    out->velocity_choice = std::move(r.velocity_choice);
    out->highest_mode_hz = r.highest_mode_hz;
    out->final_time = r.final_state.t;
    out->losses = losses_of(system, r.final_state);
    const std::vector<std::string> names = event_names(system);
    for (const Event& e : r.events) out->events.emplace_back(e.time, names[std::size_t(e.index)], e.direction);
    out->settle = settle;
    return out;
}

// An initial q or v from Python as the system's vector; its size and entries are checked by simulate()
// and periodic_orbit() (check_initial, solver/state.hpp).
template <class System>
std::optional<typename System::Vector> initial_vector(const System& system, const std::optional<Eigen::VectorXd>& x,
                                                      const char* name) {
    if (!x) return std::nullopt;
    if (x->size() != system.size())
        detail::fail(name, " must have ", system.size(), " entries (one per DOF), got ", x->size());
    return typename System::Vector(*x);
}

// The raw output handed to camfollower.results.Result: channel names, DOF names, a channels x rows
// view on the C++ buffer (kept alive by the view's base), statistics.
inline py::dict dict_of(const std::shared_ptr<RunOutput>& out) {
    const RunOutput& result = *out;
    const Recording& rec = result.recording;
    auto* keep = new std::shared_ptr<RunOutput>(out);
    py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<RunOutput>*>(p); });
    const auto channels = static_cast<py::ssize_t>(rec.names.size());
    const auto rows = static_cast<py::ssize_t>(rec.rows);
    const auto stride = static_cast<py::ssize_t>(sizeof(double));
    py::array_t<double> data({channels, rows}, {stride * static_cast<py::ssize_t>(rec.capacity), stride},
                             rec.data.data(), base);
    py::dict d;
    d["names"] = rec.names;
    d["dofs"] = rec.dofs;
    d["data"] = data;
    const SolverStatistics& st = result.report.stats;
    py::dict stats;
    stats["steps"] = st.steps;
    stats["newton_iterations"] = st.newton_iterations;
    stats["mean_iterations"] = st.mean_iterations();
    stats["max_iterations_in_a_step"] = st.max_iterations_in_a_step;
    stats["halvings"] = st.halvings;
    stats["time_step"] = result.time_step;
    stats["decimation"] = result.decimation;
    stats["cancelled"] = result.report.cancelled;
    stats["backend"] = result.backend;
    stats["method"] = result.method;
    stats["requested_method"] = result.requested_method;
    if (!result.method_choice.empty()) stats["method_choice"] = result.method_choice;
    if (!result.velocity_choice.empty()) stats["velocity_choice"] = result.velocity_choice;
    stats["evaluations"] = st.evaluations;
    stats["rejected_steps"] = st.rejected_steps;
    stats["stiff_steps"] = st.stiff_steps;
    stats["highest_mode_hz"] = result.highest_mode_hz;
    stats["steps_per_shortest_period"] = 1.0 / (result.highest_mode_hz * result.time_step);
    const SettleReport& sr = result.settle_report;
    if (sr.requested) {
        py::dict settle;
        settle["settled"] = sr.settled;
        settle["revolutions"] = sr.revolutions;
        settle["change"] = sr.change;
        settle["change_absolute"] = sr.change_absolute;
        settle["tolerance"] = out->settle.tolerance;
        settle["history"] = sr.history;
        stats["settle"] = settle;
    }
    d["stats"] = stats;
    py::dict losses;
    for (const auto& [name, intervals] : out->losses) {
        py::list l;
        for (const auto& [a, b] : intervals) l.append(py::make_tuple(a, b));
        losses[py::str(name)] = l;
    }
    d["contact_loss"] = losses;
    py::list events;
    for (const auto& [time, name, direction] : out->events)
        events.append(py::make_tuple(time, name, direction > 0 ? "made" : "lost"));
    d["events"] = events;
    d["final_time"] = out->final_time;
    return d;
}

// Takes the GIL: false when Ctrl-C is pending (KeyboardInterrupt) or progress(done, total) raises or
// returns False; a Python error is kept in `error`, to be raised once the run has stopped.
inline bool python_says_go_on(const py::object& progress, std::uint64_t done, std::uint64_t total,
                              std::optional<py::error_already_set>& error) {
    py::gil_scoped_acquire acquire;
    try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!progress.is_none()) {
            const py::object keep_going = progress(done, total);
            if (keep_going.is_none()) return true;
            // True/False (or NumPy's bool); anything else is a mistake, not a vote to go on.
            const std::string type = py::str(py::type::handle_of(keep_going).attr("__name__"));
            if (!py::isinstance<py::bool_>(keep_going) && type != "bool" && type != "bool_") {
                PyErr_SetString(
                    PyExc_TypeError,
                    ("progress(steps_done, steps_planned) must return None, True or False, got " + type).c_str());
                throw py::error_already_set();
            }
            if (!keep_going.cast<bool>()) return false;
        }
    } catch (py::error_already_set& e) {
        error.emplace(std::move(e));
        return false;
    }
    return true;
}

inline RunOptions run_options(double duration, std::size_t decimation, double record_from, double max_output_bytes,
                              const SettleOptions& settle) {
    RunOptions options;
    options.settle = settle;
    options.duration = duration;
    options.record.decimation = decimation;
    options.record.from_time = record_from;
    options.record.max_bytes = max_output_bytes;
    return options;
}

// One run with the GIL released (Ctrl-C and the progress callback honoured), as dict_of.
template <class System>
py::dict run_system(const System& system, double duration, const SolverSettings& settings, std::size_t decimation,
                    double record_from, double max_output_bytes, const py::object& progress, double progress_interval,
                    const SettleOptions& settle, const std::optional<Eigen::VectorXd>& q0 = std::nullopt,
                    const std::optional<Eigen::VectorXd>& v0 = std::nullopt) {
    using Vector = typename System::Vector;
    const std::optional<Vector> q_start = initial_vector<System>(system, q0, "initial q");
    const std::optional<Vector> v_start = initial_vector<System>(system, v0, "initial v");
    RunOptions options = run_options(duration, decimation, record_from, max_output_bytes, settle);
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
        return python_says_go_on(progress, done, planned, python_error);
    };
    std::shared_ptr<RunOutput> out;
    {
        py::gil_scoped_release release;
        out = output_of(system, simulate(system, settings, options, q_start, v_start), settle);
    }
    if (python_error) throw std::move(*python_error);
    return dict_of(out);
}

// One case of simulate_many: its run (called without the GIL) and its own options.
struct ManyCase {
    std::function<std::shared_ptr<RunOutput>(const RunOptions&)> run;
    RunOptions options;
};

// The cases on `threads` threads (0: one per hardware thread) with the GIL released. Each entry of the
// returned list: the run's dict, a (Python exception type name, message) pair for a case that failed,
// or None for a case not started because the call was cancelled: the progress callback
// (cases done, cases) returned False or raised, or Ctrl-C (KeyboardInterrupt raised once every
// started case has stopped).
inline py::list run_many(std::vector<ManyCase>& cases, unsigned threads, const py::object& progress,
                         double progress_interval) {
    detail::require_positive(progress_interval, "progress_interval", "(s)");
    (void)worker_threads(threads, cases.size());
    std::atomic<bool> stop{false};
    std::atomic<std::size_t> finished{0};
    std::mutex python_mutex;  // guards `last` and python_error
    auto last = std::chrono::steady_clock::now();
    std::optional<py::error_already_set> python_error;
    // Polled by every run every 2048 steps: after progress_interval seconds one thread takes the GIL,
    // honours Ctrl-C (on the main thread, which works on cases too) and calls progress.
    auto poll = [&](std::uint64_t, std::uint64_t) {
        if (stop.load()) return false;
        std::unique_lock<std::mutex> lock(python_mutex, std::try_to_lock);
        if (!lock.owns_lock()) return true;
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last).count() < progress_interval) return true;
        last = now;
        if (!python_says_go_on(progress, finished.load(), cases.size(), python_error)) stop = true;
        return !stop.load();
    };
    struct Outcome {
        std::shared_ptr<RunOutput> output;
        const char* error_type = nullptr;
        std::string message;
    };
    std::vector<Outcome> outcomes(cases.size());
    {
        py::gil_scoped_release release;
        parallel_for(cases.size(), threads, [&](std::size_t i) {
            if (stop.load()) return;
            ManyCase& c = cases[i];
            c.options.progress = poll;
            c.options.progress_every = 2048;
            Outcome& o = outcomes[i];
            try {
                o.output = c.run(c.options);
            } catch (const std::bad_alloc&) {
                o.error_type = "MemoryError";
                o.message = "out of memory";
            } catch (const std::invalid_argument& e) {
                o.error_type = "ValueError";
                o.message = e.what();
            } catch (const std::exception& e) {
                o.error_type = "RuntimeError";
                o.message = e.what();
            } catch (...) {
                o.error_type = "RuntimeError";
                o.message = "unknown error";
            }
            finished.fetch_add(1);
        });
    }
    if (python_error) throw std::move(*python_error);
    py::list out;
    for (const Outcome& o : outcomes) {
        if (o.output) out.append(dict_of(o.output));
        else if (o.error_type) out.append(py::make_tuple(o.error_type, o.message));
        else out.append(py::none());
    }
    return out;
}

// Binds _run(system, ...) for one system type: camfollower.simulate() calls it and wraps the output in
// a Result. `run` is run_system or a dispatcher over several system types.
template <class System, class Run>
void bind_run(py::module_& m, Run run) {
    m.def(
        "_run",
        [run](const System& system, const SolverSettings& settings, double duration, std::size_t decimation,
              double record_from, double max_output_bytes, const py::object& progress, double progress_interval,
              std::optional<double> settle_period, const std::vector<int>& settle_dofs, double settle_tolerance,
              int settle_min_revolutions, int settle_max_revolutions, const std::optional<Eigen::VectorXd>& q0,
              const std::optional<Eigen::VectorXd>& v0) {
            const SolverSettings s = as_run(settings);
            SettleOptions settle;
            if (settle_period) {
                settle.enabled = true;
                settle.period = *settle_period;
                settle.dofs = settle_dofs;
                settle.tolerance = settle_tolerance;
                settle.min_revolutions = settle_min_revolutions;
                settle.max_revolutions = settle_max_revolutions;
            }
            return run(system, duration, s, decimation, record_from, max_output_bytes, progress, progress_interval,
                       settle, q0, v0);
        },
        py::arg("system"), py::arg("settings"), py::arg("duration"), py::arg("decimation"), py::arg("record_from"),
        py::arg("max_output_bytes"), py::arg("progress"), py::arg("progress_interval"),
        py::arg("settle_period") = py::none(), py::arg("settle_dofs") = std::vector<int>{},
        py::arg("settle_tolerance") = 1e-4, py::arg("settle_min_revolutions") = 2,
        py::arg("settle_max_revolutions") = 200, py::arg("q0") = py::none(), py::arg("v0") = py::none(),
        "Internal: camfollower.simulate() calls this and wraps the output in a Result.");
}

// Shooting for the periodic steady state (solver/shooting.hpp), GIL released; Ctrl-C cancels (checked
// every revolution). Returns the orbit as a dict for camfollower.periodic.
template <class System>
py::dict shoot_system(const System& system, const SolverSettings& settings, const ShootingOptions& options,
                      const std::optional<Eigen::VectorXd>& q0, const std::optional<Eigen::VectorXd>& v0) {
    using Vector = typename System::Vector;
    const std::optional<Vector> q_start = initial_vector<System>(system, q0, "initial q");
    const std::optional<Vector> v_start = initial_vector<System>(system, v0, "initial v");
    std::optional<py::error_already_set> python_error;
    auto keep_going = [&] {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() == 0) return true;
        python_error.emplace();
        return false;
    };
    PeriodicOrbit o;
    {
        py::gil_scoped_release release;
        o = periodic_orbit(system, settings, options, q_start, v_start, keep_going);
    }
    if (python_error) throw std::move(*python_error);
    py::dict d;
    d["converged"] = o.converged;
    d["cancelled"] = o.cancelled;
    d["iterations"] = o.iterations;
    d["monodromies"] = o.monodromies;
    d["monodromy_method"] = o.monodromies ? monodromy_method_name(o.monodromy_method) : "";
    d["variational_revolutions"] = o.variational_revolutions;
    d["mismatch"] = o.mismatch;
    d["history"] = o.history;
    d["q"] = o.q;
    d["v"] = o.v;
    d["q_scale"] = o.q_scale;
    d["v_scale"] = o.v_scale;
    d["monodromy"] = o.monodromy;
    d["monodromy_at_orbit"] = o.monodromy_at_orbit;
    d["multipliers"] = Eigen::VectorXcd(o.multipliers);
    d["revolutions"] = o.revolutions;
    d["steps"] = o.stats.steps;
    d["newton_iterations"] = o.stats.newton_iterations;
    d["halvings"] = o.stats.halvings;
    d["period"] = options.period;
    d["start_time"] = options.start_time;
    d["tolerance"] = options.tolerance;
    return d;
}

template <class System, class Shoot>
void bind_shoot(py::module_& m, Shoot shoot_fn) {
    m.def(
        "_shoot",
        [shoot_fn](const System& system, const SolverSettings& settings, std::optional<double> period,
                   double start_time, double tolerance, int shooting_max_iterations, int warmup_revolutions,
                   double perturbation, bool multipliers, const std::optional<Eigen::MatrixXd>& monodromy,
                   const std::optional<Eigen::VectorXd>& q0, const std::optional<Eigen::VectorXd>& v0,
                   const std::string& monodromy_method) {
            const SolverSettings s = as_run(settings);
            ShootingOptions o;
            if (period) o.period = *period;
            o.start_time = start_time;
            o.tolerance = tolerance;
            o.max_iterations = shooting_max_iterations;
            o.warmup_revolutions = warmup_revolutions;
            o.perturbation = perturbation;
            o.multipliers = multipliers;
            if (monodromy) o.monodromy = *monodromy;
            o.monodromy_method = monodromy_method_from_name(monodromy_method);
            return shoot_fn(system, s, o, q0, v0);
        },
        py::arg("system"), py::arg("settings"), py::arg("period"), py::arg("start_time"), py::arg("tolerance"),
        py::arg("shooting_max_iterations"), py::arg("warmup_revolutions"), py::arg("perturbation"),
        py::arg("multipliers"), py::arg("monodromy"), py::arg("q0"), py::arg("v0"),
        py::arg("monodromy_method") = "auto",
        "Internal: camfollower.periodic_steady_state() calls this and wraps the output in a PeriodicOrbit.");
}

}  // namespace camfollower::python
