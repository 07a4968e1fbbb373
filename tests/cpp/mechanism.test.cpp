// The mechanism builder: assembly, bad input, the paper preset against the original 7-DOF model.
#include <catch2/catch.hpp>

#include <cmath>

#include "camfollower/camfollower.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "run.hpp"

using namespace camfollower;

TEST_CASE("paper preset equals the original 7-DOF model: matrices, equilibrium, modes, one revolution") {
    const CamFollowerModel old_model;
    const Mechanism<7> preset = presets::paper();
    CHECK((preset.mass() - old_model.mass()).cwiseAbs().maxCoeff() == 0.0);
    CHECK((preset.damping() - old_model.damping()).cwiseAbs().maxCoeff() == 0.0);
    CHECK((preset.stiffness() - old_model.stiffness()).cwiseAbs().maxCoeff() == 0.0);
    const double q_scale = old_model.initial_state().cwiseAbs().maxCoeff();
    CHECK((preset.initial_displacement() - old_model.initial_state()).cwiseAbs().maxCoeff() <= 1e-12 * q_scale);

    // Accelerations and contact forces are fixed by a residual whose terms (K q ~ 1e6 N) cancel to
    // ~200 N, so their last ~8 (acceleration) and ~10 (force) digits are rounding: the original model
    // run with its two linear solvers (same equations, other rounding) shows that spread. The preset
    // must agree with the original to 1e-12 in displacement and within that spread elsewhere.
    NewmarkSettings s;
    const auto a = run(old_model, s, old_model.period(), 1);
    const auto b = run(preset, s, preset.period(), 1);
    NewmarkSettings lu = s;
    lu.linear_solver = LinearSolver::dense_lu;
    const auto c = run(old_model, lu, old_model.period(), 1);
    REQUIRE(a.rows == b.rows);
    REQUIRE(a.rows == c.rows);
    struct Spread {
        double q = 0, a = 0, force = 0;
    };
    auto spread = [&](const Histories<CamFollowerModel>& x, const auto& y, const char* force_y) {
        Spread d;
        for (std::size_t i = 0; i < x.q.size(); ++i) {
            d.q = std::max(d.q, std::abs(x.q[i] - y.q[i]));
            d.a = std::max(d.a, std::abs(x.a[i] - y.a[i]));
        }
        for (std::size_t i = 0; i < x.rows; ++i)
            d.force = std::max(d.force, std::abs(x.channel("contact_force")[i] - y.channel(force_y)[i]));
        return d;
    };
    double qmax = 0, amax = 0, fmax = 0;
    for (std::size_t i = 0; i < a.q.size(); ++i) qmax = std::max(qmax, std::abs(a.q[i])), amax = std::max(amax, std::abs(a.a[i]));
    for (std::size_t i = 0; i < a.rows; ++i) fmax = std::max(fmax, a.channel("contact_force")[i]);
    const Spread preset_vs_old = spread(a, b, "cam.force"), rounding = spread(a, c, "contact_force");
    INFO("relative differences over one revolution, preset vs original: q " << preset_vs_old.q / qmax << ", a "
         << preset_vs_old.a / amax << ", force " << preset_vs_old.force / fmax << "; original, two linear solvers: q "
         << rounding.q / qmax << ", a " << rounding.a / amax << ", force " << rounding.force / fmax);
    CHECK(preset_vs_old.q <= 1e-12 * qmax);
    CHECK(preset_vs_old.a <= 10 * rounding.a);
    CHECK(preset_vs_old.force <= 10 * rounding.force);
    CHECK(a.stats.newton_iterations == b.stats.newton_iterations);

    // Natural frequencies at three cam angles.
    for (double theta_deg : {0.0, 100.0, 290.0}) {
        const double theta = degrees_to_radians(theta_deg);
        const ModalResult old_modes = modal_analysis(old_model, theta);
        const auto q = preset.static_equilibrium(theta);
        const Eigen::GeneralizedSelfAdjointEigenSolver<Mechanism<7>::Matrix> eig(preset.tangent_stiffness(theta, q),
                                                                                  preset.mass());
        const Eigen::Matrix<double, 7, 1> f = eig.eigenvalues().cwiseSqrt() / two_pi;
        INFO("theta = " << theta_deg << " deg");
        CHECK((f - old_modes.frequencies_hz).cwiseAbs().maxCoeff() <= 1e-12 * old_modes.frequencies_hz.maxCoeff());
    }
}
