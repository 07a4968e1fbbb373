// SPDX-License-Identifier: BSD-3-Clause
// camfollower command line (CLI11): every subcommand works on a config file (docs/config.md); without
// one, kinematics and modes describe the paper's mechanism.
//   camfollower kinematics [CONFIG] [--rpm RPM]   per contact: pressure angle, curvature, lift, acceleration
//   camfollower modes [CONFIG] [--theta DEG] [--count N]   natural frequencies, contacts linearized at a cam angle
//   camfollower run CONFIG [-o FILE]              simulate the case, CSV of every recorded channel
//   camfollower export CONFIG -o FILE [--contact NAME] [--unit mm] [--cutter-radius R] [--points N]
//                                                 cam surface (and cutter path) for manufacturing, CSV
// Exit status: 0 done, 1 the config or the run failed, 2 the command line is wrong (usage); every error
// is one line "camfollower: error: ..." on stderr.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>

#include "camfollower/camfollower.hpp"
#include "camfollower/geometry/export.hpp"
#include "config/case_config.hpp"
#include "config/force_closure.hpp"
#include "output_file.hpp"
#include "camfollower/precompiled.hpp"  // simulate() for the library's mechanisms, compiled once

namespace cf = camfollower;

namespace {

// A number as the command line's messages show it: an integer in full, anything else like %g (never
// DBL_MAX's 309 digits).
std::string shown(double v) {
    char text[32];
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) std::snprintf(text, sizeof text, "%.0f", v);
    else std::snprintf(text, sizeof text, "%.6g", v);
    return text;
}

// A numeric option's check: finite and in [lo, hi] (hi = inf: no upper bound; `what`: "a camshaft
// speed", `unit`: " rpm"). CLI11's own checks let NaN through (every comparison with it is false) and
// print DBL_MAX in full. A text that is not a number is left to CLI11's conversion, which names the
// option too.
CLI::Validator finite_in(double lo, double hi, const std::string& what, const std::string& unit = "") {
    const std::string range =
        std::isinf(hi) ? ">= " + shown(lo) + unit + " (finite)" : "in [" + shown(lo) + ", " + shown(hi) + "]" + unit;
    return CLI::Validator(
        [=](std::string& input) -> std::string {
            double v = 0.0;
            if (!CLI::detail::lexical_cast(input, v)) return {};
            if (std::isfinite(v) && v >= lo && v <= hi) return {};
            return (std::isnan(v) ? std::string("nan") : shown(v)) + " is not " + what + " " + range;
        },
        range);
}

// The paper's mechanism, as a case (what kinematics and modes describe without a config).
cf::config::CaseConfig paper_case() {
    return cf::config::parse_case("[camshaft]\nspeed = 750\n[preset]\nname = \"paper\"\n", "<paper preset>");
}

cf::config::CaseConfig case_from(const std::string& path) {
    return path.empty() ? paper_case() : cf::config::load_case(path);
}

// Run f on the built mechanism: the fixed-size path for the preset's 7 DOFs (as the Python module does,
// so both give the same numbers), dynamic otherwise.
template <class F>
void with_mechanism(const cf::MechanismBuilder& b, F&& f) {
    if (b.structure.size() == cf::presets::paper_dofs) f(cf::Mechanism<cf::presets::paper_dofs>(b));
    else f(cf::Mechanism<Eigen::Dynamic>(b));
}

int kinematics(const std::string& config, double rpm) {
    const cf::config::CaseConfig c = case_from(config);
    if (rpm <= 0.0) rpm = c.mechanism.camshaft_speed_rpm();
    const double omega = rpm * cf::two_pi / 60.0;
    const auto deg = cf::radians_to_degrees;
    std::printf("%s at %.6g rpm\n", c.origin.c_str(), rpm);
    const cf::config::ForceClosure closure = cf::config::check_force_closure(c.mechanism, rpm);
    std::size_t index = 0;
    for (const cf::ContactPairSpec& p : c.mechanism.contacts) {
        std::printf("contact '%s': %s follower\n", p.name.c_str(), cf::follower_type_name(p.follower));
        std::visit(
            [&](const auto& f) {
                const cf::AngleExtremum alpha = cf::max_pressure_angle(p.program, f);
                const cf::AngleExtremum rho = cf::min_surface_radius(p.program, f);
                std::printf("  max |pressure angle|:                %.4f deg at theta = %.3f deg\n",
                            std::abs(deg(alpha.value)), deg(alpha.theta));
                std::printf("  min convex cam-surface radius:       %.4f mm at theta = %.3f deg\n", 1e3 * rho.value,
                            deg(rho.theta));
            },
            p.follower);
        const auto acc = cf::detail::maximize_piecewise([&](double t) { return std::abs(p.program.evaluate(t).d2h); },
                                                        p.program.breakpoints(), 600, p.program.sampling_step());
        const auto vel = cf::detail::maximize_piecewise([&](double t) { return std::abs(p.program.evaluate(t).dh); },
                                                        p.program.breakpoints(), 600, p.program.sampling_step());
        // Lengths in mm, arm angles in degrees (as the Python command prints them).
        const bool translating = cf::is_translating(p.follower);
        const double lift_scale = translating ? 1e3 : deg(1.0);
        std::printf("  lift range:                          %.6g to %.6g %s\n", lift_scale * p.program.min_lift(),
                    lift_scale * p.program.max_lift(), translating ? "mm" : "deg");
        std::printf("  max |follower velocity| (rigid):     %.6g %s at theta = %.3f deg\n", omega * vel.value,
                    translating ? "m/s" : "rad/s", deg(vel.x));
        std::printf("  max |follower acceleration| (rigid): %.6g %s at theta = %.3f deg\n", omega * omega * acc.value,
                    translating ? "m/s^2" : "rad/s^2", deg(acc.x));
        // The force-closure check reports no contact when it could not run (a static equilibrium not
        // found; its warning says so): the kinematics above still hold.
        if (index >= closure.contacts.size()) continue;
        const cf::config::ContactClosure& k = closure.contacts[index++];
        // "30.0-89.5, 270.5-330.0" (deg), or "no".
        const auto spans = [&](const std::vector<std::pair<double, double>>& intervals) {
            std::string out;
            char span[64];
            for (const auto& [from, to] : intervals) {
                std::snprintf(span, sizeof span, "%s%.1f-%.1f", out.empty() ? "" : ", ", deg(from), deg(to));
                out += span;
            }
            return out.empty() ? std::string("no") : out;
        };
        // A grooved cam: where the rigid check puts the roller on the outer flank (as Python prints it).
        if (p.groove) {
            const std::string over = spans(k.outer_flank);
            std::printf(
                "  groove clearance %.6g mm: outer flank carries the roller (rigid) over %s deg, %d flank "
                "changes per revolution\n",
                1e3 * p.groove->clearance, over.c_str(), k.flank_changes);
        }
        // Conjugate cams: where the rigid check puts the load on the other cam.
        if (!k.conjugate.empty()) {
            const std::string over = spans(k.other_cam);
            std::printf(
                "  conjugate to '%s', which carries the load (rigid) over %s deg, %d changes of cam per "
                "revolution\n",
                k.conjugate.c_str(), over.c_str(), k.flank_changes);
        }
    }
    return 0;
}

int modes(const std::string& config, double theta_deg, int count) {
    const cf::config::CaseConfig c = case_from(config);
    const double theta = cf::degrees_to_radians(theta_deg);
    with_mechanism(c.mechanism, [&](const auto& m) {
        // All modes of a small model; the lowest `count` of a large one (sparse shift-invert).
        if (count <= 0 && m.size() > cf::dense_modes_limit) count = 20;
        const cf::MechanismModes r = cf::lowest_modes(m, theta, std::min(count, m.size()));
        std::printf("%s: natural frequencies (Hz), contacts linearized at the static equilibrium, theta = %g deg%s\n",
                    c.origin.c_str(), theta_deg,
                    r.frequencies_hz.size() < m.size()
                        ? cf::detail::concat(" (lowest ", r.frequencies_hz.size(), " of ", m.size(), ")").c_str()
                        : "");
        const std::vector<std::string> names = m.dof_names();
        for (Eigen::Index k = 0; k < r.frequencies_hz.size(); ++k) {
            Eigen::Index dominant = 0;
            r.shapes.col(k).cwiseAbs().maxCoeff(&dominant);
            std::printf("mode %-3ld %14.2f   largest motion: %s\n", long(k + 1), r.frequencies_hz[k],
                        names[std::size_t(dominant)].c_str());
        }
    });
    return 0;
}

int run(const std::string& config, std::string output) {
    const cf::config::CaseConfig c = cf::config::load_case(config);
    if (output.empty()) output = c.output.file;
    if (output.empty()) cf::detail::fail(config, ": no output file: set [output] file or give -o FILE");
    cf::detail::require_output_target(output, "output", {config});
    // A mechanism that does not hold its follower on the cam runs, but says so first (docs/config.md).
    for (const std::string& w : cf::config::check_force_closure(c.mechanism).warnings)
        std::fprintf(stderr, "camfollower: warning: %s\n", cf::detail::message_text(w).c_str());
    with_mechanism(c.mechanism, [&](const auto& m) {
        const double period = m.period();
        cf::SolverSettings settings = c.solver.settings;
        settings.time_step = c.solver.time_step_for(period);
        cf::RunOptions options;
        options.duration = c.solver.duration_for(period);
        options.record.decimation = std::size_t(c.output.decimation);
        if (c.output.record_last_revolutions > 0.0)
            options.record.from_time = options.duration - c.output.record_last_revolutions * period;
        if (c.solver.settle) {
            options.settle.enabled = true;
            options.settle.period = period;
            options.settle.tolerance = c.solver.settle_tolerance;
            options.settle.min_revolutions = c.solver.settle_min_revolutions;
            options.settle.max_revolutions = c.solver.settle_max_revolutions;
            const std::vector<std::string> names = m.dof_names();
            std::vector<std::string> watched = c.solver.settle_dofs;
            if (watched.empty())
                for (const auto& pair : m.contacts()) watched.push_back(pair.spec().follower_dof);
            for (const std::string& d : watched) {
                const auto it = std::find(names.begin(), names.end(), d);
                if (it == names.end()) cf::detail::fail(config, ": [solver] settle_dofs: unknown DOF '", d, "'");
                options.settle.dofs.push_back(int(it - names.begin()));
            }
        }
        const auto result = cf::simulate(m, settings, options);
        cf::cli::write_recording_csv(output, result.recording, config);
        const cf::SolverStatistics& stats = result.report.stats;
        // Newmark under a tolerance (named: auto does not take it).
        const std::string ran = result.method;
        if (settings.tolerance && cf::is_newmark_family(cf::method_from_name(ran)))
            std::printf(
                "%zu rows, %zu channels (%s under tolerance %.3g: %llu steps, %llu rejected, %.3f Newton "
                "iterations/step, output every %.4g s)",
                result.recording.rows, result.recording.names.size(), result.method, *settings.tolerance,
                static_cast<unsigned long long>(stats.steps), static_cast<unsigned long long>(stats.rejected_steps),
                stats.mean_iterations(), settings.time_step);
        else if (settings.tolerance)
            std::printf(
                "%zu rows, %zu channels (%s%s: %llu steps, %llu rejected, %llu force evaluations, output every %.4g s)",
                result.recording.rows, result.recording.names.size(), result.method,
                cf::is_automatic(settings.method) ? ", chosen by auto" : "",
                static_cast<unsigned long long>(stats.steps), static_cast<unsigned long long>(stats.rejected_steps),
                static_cast<unsigned long long>(stats.evaluations), settings.time_step);
        else
            std::printf("%zu rows, %zu channels (%s%s: %llu steps, dt = %.4g s, %.3f Newton iterations/step)",
                        result.recording.rows, result.recording.names.size(), result.method,
                        cf::is_automatic(settings.method) ? ", chosen by auto" : "",
                        static_cast<unsigned long long>(stats.steps), settings.time_step, stats.mean_iterations());
        if (c.solver.settle)
            std::printf(", %s after %d revolutions (change %.3g)", result.settle.settled ? "settled" : "NOT settled",
                        result.settle.revolutions, result.settle.change);
        for (std::size_t i = 0; i < m.contacts().size(); ++i) {
            double lost = 0.0;
            for (const auto& [a, b] :
                 std::decay_t<decltype(m)>::contact_loss(result.final_state.workspace, i, result.final_state.t))
                lost += b - a;
            std::printf(", '%s' lost contact %.4g s", m.contacts()[i].name().c_str(), lost);
        }
        std::printf(", %zu contact losses and re-contacts located", result.events.size());
        std::printf(" -> %s\n", output.c_str());
        if (!result.method_choice.empty()) std::printf("method auto took %s\n", result.method_choice.c_str());
        if (!result.velocity_choice.empty()) std::printf("%s\n", result.velocity_choice.c_str());
    });
    return 0;
}

int export_cam(const std::string& config, const std::string& output, std::string contact, const std::string& unit_name,
               double cutter_radius, std::size_t points) {
    const cf::config::CaseConfig c = cf::config::load_case(config);
    cf::detail::require_output_target(output, "output", {config});
    const cf::LengthUnit unit = cf::length_unit_from_name(unit_name);
    if (contact.empty() && !c.mechanism.contacts.empty()) contact = c.mechanism.contacts.front().name;
    std::string known;
    for (const cf::ContactPairSpec& p : c.mechanism.contacts) {
        known += (known.empty() ? "" : ", ") + p.name;
        if (p.name != contact) continue;
        std::optional<double> cutter;
        if (cutter_radius > 0.0) cutter = cutter_radius * cf::length_unit_spec(unit).metres;
        std::visit([&](const auto& f) { cf::write_cam_csv(output, f, p.program, points, cutter, unit); }, p.follower);
        std::printf("contact '%s': %zu points of the cam surface%s in %s -> %s\n", p.name.c_str(), points,
                    cutter ? " and the cutter-centre path" : "", unit_name.c_str(), output.c_str());
        return 0;
    }
    cf::detail::fail("--contact: no contact named '", contact,
                     "'; the config defines: ", known.empty() ? "none" : known);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"camfollower: dynamics of flexible cam-follower mechanisms (SI units; config format: docs/config.md)"};
    app.require_subcommand(1);
    app.footer("Exit status: 0 done, 1 the config or the run failed, 2 a command-line (usage) error.");
    const double min_rpm = cf::detail::min_camshaft_speed * 30.0 / cf::pi;
    const double max_rpm = cf::detail::max_camshaft_speed * 30.0 / cf::pi;
    std::string config, output;
    double rpm = 0.0, theta_deg = 0.0;

    CLI::App* kin = app.add_subcommand("kinematics",
                                       "Per contact: largest pressure angle, smallest cam-surface radius, lift range, "
                                       "rigid velocity and acceleration");
    kin->add_option("config", config, "config file (default: the paper's mechanism)")->check(CLI::ExistingFile);
    kin->add_option("--rpm", rpm, "camshaft speed for the velocity and acceleration (default: the config's)")
        ->check(finite_in(min_rpm, max_rpm, "a camshaft speed", " rpm"));

    CLI::App* mod =
        app.add_subcommand("modes", "Natural frequencies of the mechanism, contacts linearized at a cam angle");
    mod->add_option("config", config, "config file (default: the paper's mechanism)")->check(CLI::ExistingFile);
    mod->add_option("--theta", theta_deg, "camshaft angle of the linearization, deg")
        ->check(finite_in(-1e6, 1e6, "a cam angle", " deg"));
    int mode_count = 0;
    mod->add_option("--count", mode_count, "how many of the lowest modes (default: all; 20 above 200 DOFs)")
        ->check(finite_in(1, 100000, "a number of modes"));

    CLI::App* runc =
        app.add_subcommand("run", "Simulate the case the config describes; write every recorded channel as CSV");
    runc->add_option("config", config, "config file")->required()->check(CLI::ExistingFile);
    CLI::Option* run_output = runc->add_option("-o,--output", output, "CSV file (default: the config's [output] file)");

    CLI::App* exp =
        app.add_subcommand("export",
                           "Cam surface (and cutter-centre path) of one contact's cam for manufacturing, as CSV "
                           "with units, rotation direction and zero mark in its header");
    std::string contact, unit = "mm";
    double cutter_radius = 0.0;
    std::size_t points = 3600;
    exp->add_option("config", config, "config file")->required()->check(CLI::ExistingFile);
    CLI::Option* export_output = exp->add_option("-o,--output", output, "CSV file")->required();
    exp->add_option("--contact", contact, "contact whose cam to export (default: the first)");
    exp->add_option("--unit", unit, "length unit of the file")
        ->check(CLI::IsMember({"m", "mm", "um", "inch"}))
        ->capture_default_str();
    exp->add_option("--cutter-radius", cutter_radius,
                    "radius of the milling cutter or grinding wheel, in --unit (0: no cutter path)")
        ->check(finite_in(0.0, std::numeric_limits<double>::infinity(), "a radius"));
    exp->add_option("--points", points, "points round the cam")
        ->check(finite_in(8, double(cf::detail::max_points), "a number of points"))
        ->capture_default_str();

    try {
        app.parse(argc, argv);
        // What CLI11 cannot check alone: an empty -o (run would fall back to the config's own file) and
        // a cutter radius of at most a kilometre in the file's unit.
        for (const CLI::Option* o : {run_output, export_output})
            if (o->count() > 0 && output.empty())
                throw CLI::ValidationError("-o/--output", "must name a file, got an empty string");
        // The compiled program writes CSV only; the Python command writes DXF (ezdxf).
        if (*exp && output.size() >= 4) {
            std::string ext = output.substr(output.size() - 4);
            for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
            if (ext == ".dxf")
                throw CLI::ValidationError("-o/--output",
                                           "this program writes the cam as CSV; for DXF use the Python "
                                           "command (pip install camfollower[dxf]): camfollower export");
        }
        if (*exp && cutter_radius > 0.0) {
            const double metres = cf::length_unit_spec(cf::length_unit_from_name(unit)).metres;
            const double most = cf::detail::max_part_length / metres;
            if (cutter_radius > most)
                throw CLI::ValidationError(
                    "--cutter-radius", shown(cutter_radius) + " is not a radius in [0, " + shown(most) + "] " + unit);
        }
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // CLI11 would print the bare message and exit with its own codes (105, 106, 109, ...).
        std::fprintf(stderr, "camfollower: error: %s\n", cf::detail::message_text(e.what()).c_str());
        return 2;
    }
    try {
        if (*kin) return kinematics(config, rpm);
        if (*mod) return modes(config, theta_deg, mode_count);
        if (*runc) return run(config, output);
        if (*exp) return export_cam(config, output, contact, unit, cutter_radius, points);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "camfollower: error: %s\n", e.what());
        return 1;
    }
    return 2;
}
