// camfollower command line: kinematics summary of the paper cam (more subcommands to come).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "camfollower/camfollower.hpp"

namespace cf = camfollower;

namespace {
int kinematics(double rpm) {
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
    std::printf("max |pressure angle|, rise:   %+.4f deg at theta = %.3f deg\n",
                cf::radians_to_degrees(rise.value), cf::radians_to_degrees(rise.theta));
    std::printf("max |pressure angle|, return: %+.4f deg at theta = %.3f deg\n",
                cf::radians_to_degrees(ret.value), cf::radians_to_degrees(ret.theta));
    std::printf("min cam-surface radius of curvature (convex): %.4f mm at theta = %.3f deg\n",
                rho.value * 1e3, cf::radians_to_degrees(rho.theta));
    std::printf("min cam-surface radius of curvature on the rise/return flanks: %.4f mm at theta = %.3f deg\n",
                rho_flank.value * 1e3, cf::radians_to_degrees(rho_flank.theta));
    std::printf("max theoretical follower acceleration at %.0f rpm: %.4f m/s^2 at theta = %.3f deg\n",
                rpm, omega * omega * amax, cf::radians_to_degrees(at));
    return 0;
}
}  // namespace

int main(int argc, char** argv) {
    try {
        if (argc >= 2 && std::strcmp(argv[1], "kinematics") == 0)
            return kinematics(argc >= 3 ? std::stod(argv[2]) : 750.0);
        std::fprintf(stderr, "usage: camfollower kinematics [rpm]\n");
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "camfollower: error: %s\n", e.what());
        return 1;
    }
}
