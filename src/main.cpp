// camfollower command line.
//   camfollower kinematics [rpm]         the paper cam's kinematic summary
//   camfollower run CONFIG [-o FILE]     simulate a case from a config file (see examples/), CSV out
//   camfollower modes [theta_deg]        natural frequencies of the paper model (config-free)
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "camfollower/camfollower.hpp"
#include "config.hpp"

namespace cf = camfollower;

namespace {

int kinematics(double rpm) {
    cf::detail::require_positive(rpm, "rpm");
    const cf::DiskCam cam = cf::DiskCam::paper_default();
    const double omega = rpm * cf::two_pi / 60.0;
    const auto rise = cam.max_pressure_angle_rise();
    const auto ret = cam.max_pressure_angle_return();
    const auto rho = cam.min_surface_radius();
    const auto rho_flank = cam.min_surface_radius(cam.geometry().offset, true);
    double amax = 0.0, at = 0.0;
    for (int k = 0; k < 360000; ++k) {
        const double t = cf::two_pi * k / 360000.0, a = std::abs(cam.program().evaluate(t).d2h);
        if (a > amax) amax = a, at = t;
    }
    std::printf("paper cam: r_b = 30 mm, r_r = 8 mm, e = 10 mm, 10 mm modified-trapezoid rise/return\n");
    std::printf("max |pressure angle|, rise:   %.4f deg (alpha = %+.4f deg) at theta = %.3f deg\n",
                std::abs(cf::radians_to_degrees(rise.value)), cf::radians_to_degrees(rise.value),
                cf::radians_to_degrees(rise.theta));
    std::printf("max |pressure angle|, return: %.4f deg (alpha = %+.4f deg) at theta = %.3f deg\n",
                std::abs(cf::radians_to_degrees(ret.value)), cf::radians_to_degrees(ret.value),
                cf::radians_to_degrees(ret.theta));
    std::printf("min cam-surface radius of curvature (convex): %.4f mm at theta = %.3f deg\n", rho.value * 1e3,
                cf::radians_to_degrees(rho.theta));
    std::printf("min cam-surface radius of curvature on the rise/return flanks: %.4f mm at theta = %.3f deg\n",
                rho_flank.value * 1e3, cf::radians_to_degrees(rho_flank.theta));
    std::printf("max theoretical follower acceleration at %.0f rpm: %.4f m/s^2 at theta = %.3f deg\n", rpm,
                omega * omega * amax, cf::radians_to_degrees(at));
    return 0;
}

int modes(double theta_deg) {
    const cf::CamFollowerModel model;
    const auto with = cf::modal_analysis(model, cf::degrees_to_radians(theta_deg));
    const auto without = cf::modal_analysis(model, 0.0, false);
    std::printf("natural frequencies of the paper model (Hz); contact linearized at theta = %g deg\n", theta_deg);
    std::printf("%-6s %12s %12s %12s\n", "mode", "contact", "no contact", "Table 3");
    // The paper's Table 3, one value per mode of its model.
    const std::array<int, cf::presets::paper_dofs> table3 = {2447, 2447, 5711, 12777, 13990, 17009, 17009};
    for (std::size_t k = 0; k < table3.size(); ++k)
        std::printf("f0%-4zu %12.1f %12.1f %12d\n", k + 1, with.frequencies_hz[Eigen::Index(k)],
                    without.frequencies_hz[Eigen::Index(k)], table3[k]);
    return 0;
}

int run(const std::string& config_path, const std::string& output_override) {
    const cf::cli::RunConfig c = cf::cli::load_config(config_path);
    const std::string output = output_override.empty() ? c.output : output_override;
    const cf::CamFollowerModel model(c.parameters, cf::MotionProgram::paper_default(), c.defects);
    cf::NewmarkSettings settings;
    settings.time_step = c.time_step > 0 ? c.time_step : model.period() / c.steps_per_revolution;
    cf::RunOptions options;
    options.duration = c.revolutions * model.period();
    options.record.decimation = static_cast<std::size_t>(c.decimation);
    const auto run = cf::simulate(model, settings, options);
    const cf::Recording& r = run.recording;
    const std::size_t n = r.dofs.size();
    const std::string tmp = output + ".tmp";
    {
        std::ofstream out(tmp);
        if (!out) cf::detail::fail("output: cannot open '", output, "' for writing");
        out.precision(12);
        out << "t_s,theta_rad";
        for (const std::string& d : r.dofs) out << ",q_" << d << "_m";
        for (const std::string& d : r.dofs) out << ",a_" << d << "_m_s2";
        out << ",contact_force_N,contact_stiffness_N_m,pressure_angle_rad,in_contact\n";
        const double *t = r.channel("t"), *theta = r.channel("theta"), *force = r.channel("contact_force"),
                     *stiffness = r.channel("contact_stiffness"), *alpha = r.channel("pressure_angle"),
                     *contact = r.channel("in_contact");
        for (std::size_t i = 0; i < r.rows; ++i) {
            out << t[i] << ',' << theta[i];
            for (std::size_t k = 0; k < n; ++k) out << ',' << r.channel(r.block(0) + k)[i];
            for (std::size_t k = 0; k < n; ++k) out << ',' << r.channel(r.block(2) + k)[i];
            out << ',' << force[i] << ',' << stiffness[i] << ',' << alpha[i] << ',' << int(contact[i]) << '\n';
        }
        if (!out.flush()) cf::detail::fail("output: writing '", output, "' failed");
    }
    if (std::rename(tmp.c_str(), output.c_str()) != 0) {
        std::remove(tmp.c_str());
        cf::detail::fail("output: cannot rename the temporary file to '", output, "'");
    }
    double lost = 0;
    for (const auto& [a, b] : cf::CamFollowerModel::contact_loss(run.final_state.workspace, run.final_state.t))
        lost += b - a;
    const cf::SolverStatistics& stats = run.report.stats;
    std::printf("%zu rows (%llu steps, dt = %.4g s, %.3f Newton iterations/step), contact lost %.4g s -> %s\n",
                r.rows, static_cast<unsigned long long>(stats.steps), settings.time_step, stats.mean_iterations(), lost,
                output.c_str());
    return 0;
}

void usage() {
    std::fprintf(stderr,
                 "usage: camfollower kinematics [rpm]\n"
                 "       camfollower modes [theta_deg]\n"
                 "       camfollower run CONFIG.toml [-o OUTPUT.csv]\n");
}

// A whole-string number, or a clear error naming the argument.
double number_argument(const char* text, const char* name) {
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || text[used] != '\0' || !std::isfinite(v)) cf::detail::fail(name, " must be a number, got '", text, "'");
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const std::string cmd = argc >= 2 ? argv[1] : "";
        if (cmd == "kinematics") return kinematics(argc >= 3 ? number_argument(argv[2], "rpm") : 750.0);
        if (cmd == "modes") return modes(argc >= 3 ? number_argument(argv[2], "theta_deg") : 0.0);
        if (cmd == "run" && (argc == 3 || (argc == 5 && std::strcmp(argv[3], "-o") == 0)))
            return run(argv[2], argc == 5 ? argv[4] : "");
        usage();
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "camfollower: error: %s\n", e.what());
        return 1;
    }
}
