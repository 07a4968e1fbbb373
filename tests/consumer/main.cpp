// A user's tool built against the installed package: the README's C++ example, checked.
#include <camfollower/camfollower.hpp>
#include <cmath>
#include <cstdio>

int main() {
    namespace cf = camfollower;
    const cf::DiskCam cam = cf::DiskCam::paper_default();
    const double alpha = cam.kinematics(cf::degrees_to_radians(105.0)).pressure_angle();
    const cf::CamFollowerModel model;
    cf::RunOptions options;
    options.duration = 0.1 * model.period();
    options.record.decimation = 10;
    const auto result = cf::simulate(model, cf::NewmarkSettings{}, options).recording;
    const auto modes = cf::modal_analysis(model, 0.0);
    std::printf("pressure angle at 105 deg: %.6f deg; %zu rows; f01 = %.1f Hz\n",
                cf::radians_to_degrees(alpha), result.rows, modes.frequencies_hz[0]);
    const bool ok = std::isfinite(alpha) && std::abs(alpha) < 0.5 && result.rows > 0 &&
                    modes.frequencies_hz[0] > 100.0;
    return ok ? 0 : 1;
}
