// SPDX-License-Identifier: BSD-3-Clause
// A user's tool built against the installed package: the README's C++ examples, checked.
#include <camfollower/camfollower.hpp>
#include <cmath>
#include <cstdio>

int main() {
    namespace cf = camfollower;
    const cf::MotionProgram program = cf::MotionProgram::paper_default();
    const cf::TranslatingRoller roller(0.030, 0.008, 0.010);
    const double theta = cf::degrees_to_radians(105.0);
    const double alpha = roller.contact(theta, program.evaluate(theta)).pressure_angle();

    // The user's own mechanism: a flat-faced tappet on a rigid cam, a valve spring with its own mass.
    cf::MechanismBuilder b;
    b.add_dof("tappet", 0.1, {0, 1, 0});  // kg, moves along +y
    b.add_dof("spring_mid", 0.02, {0, 1, 0});
    b.add_spring("spring_top", "tappet", "spring_mid", 6e4, 0.0, 250.0);  // N/m, N s/m, preload N
    b.add_spring("spring_bottom", "spring_mid", "ground", 6e4, 0.0, 250.0);
    b.set_gravity({0, -9.81, 0});
    b.set_camshaft_speed_rpm(1500);
    b.add_contact({"cam", cf::MotionProgram::paper_default(0.008), cf::TranslatingFlat(0.030),
                   cf::HertzContact{2e8, 1.0, 0.0}, 0.0, "ground", "ground", "tappet", "ground"});
    const cf::Mechanism<> mine(b);

    cf::RunOptions options;
    options.duration = mine.period();
    options.record.decimation = 10;
    const cf::RunResult<cf::Mechanism<>> run = cf::simulate(mine, cf::SolverSettings{}, options);
    const double* force = run.recording.channel("cam.force");

    const auto preset = cf::presets::paper();  // the paper's 7-DOF model
    const auto q = preset.static_equilibrium(0.0);
    std::printf("pressure angle at 105 deg: %.6f deg; %zu rows; contact force at t = 0: %.2f N; preset y4 = %.3g m\n",
                cf::radians_to_degrees(alpha), run.recording.rows, force[0], q[3]);
    const bool ok = std::isfinite(alpha) && std::abs(alpha) < 0.5 && run.recording.rows > 0 && force[0] > 250.0 &&
                    force[0] < 260.0 && q[3] < 0.0;
    return ok ? 0 : 1;
}
