// Prints the paper cam's pressure angle at mid-rise; exits non-zero if the value is implausible.
#include <camfollower/camfollower.hpp>
#include <cmath>
#include <cstdio>

int main() {
    const camfollower::DiskCam cam = camfollower::DiskCam::paper_default();
    const double alpha = cam.kinematics(camfollower::degrees_to_radians(105.0)).pressure_angle();
    std::printf("pressure angle at 105 deg: %.6f deg\n", camfollower::radians_to_degrees(alpha));
    return std::isfinite(alpha) && std::abs(alpha) < 0.5 ? 0 : 1;
}
