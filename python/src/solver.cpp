// Bindings for include/camfollower/solver: run a simulation, get NumPy arrays (no copies).
#include <memory>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "camfollower/model/cam_follower_model.hpp"
#include "camfollower/solver/newmark.hpp"

namespace camfollower::python {

namespace {
using Result = SimulationResult<CamFollowerModel::dofs>;

// NumPy view over a vector owned by a shared result (kept alive by the array's base capsule).
template <class T>
py::array_t<T> view(const std::shared_ptr<Result>& owner, std::vector<T>& data, std::vector<py::ssize_t> shape) {
    auto* keep = new std::shared_ptr<Result>(owner);
    py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Result>*>(p); });
    return py::array_t<T>(shape, data.data(), base);
}
}  // namespace

void bind_solver(py::module_& m) {
    m.def(
        "simulate",
        [](const CamFollowerModel& model, std::optional<double> duration, std::optional<double> revolutions,
           double time_step, std::size_t decimation, std::optional<double> gamma, std::optional<double> beta,
           double hht_alpha,
           const std::string& linear_solver, double residual_tolerance, double increment_tolerance,
           int max_iterations, int max_halvings, double max_output_bytes) {
            if (duration.has_value() == revolutions.has_value())
                detail::fail("give exactly one of duration (s) or revolutions");
            double span = 0.0;
            if (revolutions) {
                detail::require_positive(*revolutions, "revolutions");
                span = *revolutions * model.period();
            } else {
                span = *duration;
            }
            // gamma and beta default to the average-acceleration rule, or to HHT's own values.
            NewmarkSettings s = NewmarkSettings::hht(hht_alpha, time_step);
            if (gamma) s.gamma = *gamma;
            if (beta) s.beta = *beta;
            s.residual_tolerance = residual_tolerance;
            s.increment_tolerance = increment_tolerance;
            s.max_iterations = max_iterations;
            s.max_halvings = max_halvings;
            if (linear_solver == "sherman_morrison") s.linear_solver = LinearSolver::sherman_morrison;
            else if (linear_solver == "dense_lu") s.linear_solver = LinearSolver::dense_lu;
            else detail::fail("linear_solver must be 'sherman_morrison' or 'dense_lu', got '", linear_solver, "'");
            auto result = std::make_shared<Result>();
            {
                py::gil_scoped_release release;
                const NewmarkSolver<CamFollowerModel> solver(model, s);
                *result = solver.run(span, decimation, max_output_bytes);
            }
            const auto rows = static_cast<py::ssize_t>(result->rows);
            const py::ssize_t n = CamFollowerModel::dofs;
            py::dict d;
            d["t"] = view(result, result->t, {rows});
            d["theta"] = view(result, result->theta, {rows});
            d["q"] = view(result, result->q, {rows, n});
            d["v"] = view(result, result->v, {rows, n});
            d["a"] = view(result, result->a, {rows, n});
            d["contact_force"] = view(result, result->contact_force, {rows});
            d["contact_stiffness"] = view(result, result->contact_stiffness, {rows});
            d["pressure_angle"] = view(result, result->pressure_angle, {rows});
            d["penetration"] = view(result, result->penetration, {rows});
            d["in_contact"] = view(result, result->in_contact, {rows}).attr("astype")("bool");
            py::list losses;
            for (const auto& [a, b] : result->contact_loss) losses.append(py::make_tuple(a, b));
            d["contact_loss"] = losses;
            py::dict stats;
            stats["steps"] = result->stats.steps;
            stats["newton_iterations"] = result->stats.newton_iterations;
            stats["mean_iterations"] = result->stats.mean_iterations();
            stats["max_iterations_in_a_step"] = result->stats.max_iterations_in_a_step;
            stats["halvings"] = result->stats.halvings;
            stats["time_step"] = result->time_step;
            stats["decimation"] = result->decimation;
            d["stats"] = stats;
            return d;
        },
        py::arg("model"), py::kw_only(), py::arg("duration") = py::none(), py::arg("revolutions") = py::none(),
        py::arg("time_step") = 3e-6, py::arg("decimation") = 1, py::arg("gamma") = py::none(), py::arg("beta") = py::none(),
        py::arg("hht_alpha") = 0.0, py::arg("linear_solver") = "sherman_morrison",
        py::arg("residual_tolerance") = 1e-10, py::arg("increment_tolerance") = 1e-10, py::arg("max_iterations") = 25,
        py::arg("max_halvings") = 6, py::arg("max_output_bytes") = 4.0 * 1024 * 1024 * 1024,
        "Integrate the model from its static equilibrium with Newmark-beta (HHT-alpha if hht_alpha < 0)\n"
        "and Newton-Raphson. Give duration (s) or revolutions. One row every `decimation` steps.\n"
        "gamma, beta default to 1/2, 1/4 (average acceleration) or, with hht_alpha, to 1/2 - alpha and\n"
        "(1 - alpha)^2 / 4. beta < 1/4 is only conditionally stable: a time_step beyond its limit is refused.\n"
        "Returns a dict of NumPy arrays: t, theta (rad), q, v, a (rows x 7, m, m/s, m/s^2),\n"
        "contact_force (N), contact_stiffness (dF/d delta, N/m), pressure_angle (rad), penetration (m),\n"
        "in_contact (bool); contact_loss: list of (start, end) times; stats: steps, iterations, halvings.\n"
        "Raises ValueError for bad input and RuntimeError when Newton fails after max_halvings.\n"
        "The GIL is released during the run.");
}

}  // namespace camfollower::python
