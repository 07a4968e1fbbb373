// SPDX-License-Identifier: BSD-3-Clause
// How smooth a motion program is, for judging a lift table: the peaks of |h'|, |h''|, |h'''| and where
// they occur, how far a smoothing fit passes from its table, and where a table's noise shows up.
//
// Noise in a table shows up first in the jerk, as an oscillation from one table point to the next. The
// report measures it at the examination sites (every piece boundary of a spline segment, i.e. its
// knots; 64 equal steps over any other segment) by the jerk's local excursion
//     e_i = |J_i - J*_i|,  J*_i the value at theta_i of the straight line through the neighbours' jerks
// (a second difference: O(step^2) for a smooth jerk, the full oscillation amplitude for noise). It
// lists the largest local maxima of e_i (angle, size) and the roughness RMS(e) / peak |J|: below 0.01
// for a smooth lift, 0.1 - 0.5 when noise dominates the jerk (pure noise: about 0.25). A built-in law whose jerk jumps
// (modified trapezoid, a segment boundary) also shows an excursion there: it is a real jerk step, not noise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "camfollower/motion/lift_peaks.hpp"
#include "camfollower/motion/lift_spline.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

struct JerkExcursion {
    double theta = 0.0;      // rad
    double excursion = 0.0;  // m/rad^3
};

struct SmoothnessReport {
    LiftPeaks peaks;                             // peak |h'|, |h''|, |h'''| (m/rad^k) and their angles (rad)
    std::size_t table_points = 0;                // points of the program's spline tables (0: none)
    FitResidual residual;                        // misses at those points (m): zero to rounding when interpolating
    double jerk_roughness = 0.0;                 // RMS jerk excursion / peak |h'''| (dimensionless)
    std::vector<JerkExcursion> jerk_excursions;  // the largest local excursions, largest first
};

// excursions: how many of the largest local jerk excursions to list.
inline SmoothnessReport smoothness(const MotionProgram& program, std::size_t excursions = 5) {
    SmoothnessReport report;
    // Sites: spline knots mapped to program angles, 64 steps over other segments, and every break.
    std::vector<double> sites = program.breakpoints();
    sites.pop_back();  // 2 pi is 0
    double squared = 0.0;
    for (const Segment& s : program.segments()) {
        if (const LiftSpline* spline = s.law.spline()) {
            for (double b : spline->breaks())
                sites.push_back(MotionProgram::wrap(s.theta_start + (b - spline->origin())));
            const FitResidual r = spline->residual();
            const std::size_t n = spline->theta().size();
            squared += r.rms * r.rms * static_cast<double>(n);
            if (report.table_points == 0 || r.max > report.residual.max) {
                report.residual.max = r.max;
                report.residual.theta_of_max = MotionProgram::wrap(s.theta_start + (r.theta_of_max - spline->origin()));
            }
            report.table_points += n;
        } else {
            for (int k = 1; k < 64; ++k) sites.push_back(s.theta_start + s.span() * k / 64.0);
        }
    }
    if (report.table_points > 0) report.residual.rms = std::sqrt(squared / static_cast<double>(report.table_points));
    std::sort(sites.begin(), sites.end());
    sites.erase(std::unique(sites.begin(), sites.end(), [](double a, double b) { return b - a <= 1e-12; }),
                sites.end());

    // Peaks: 8 samples between consecutive sites, refined around the best.
    std::vector<double> pieces = sites;
    pieces.push_back(two_pi);
    report.peaks = detail::find_lift_peaks([&](double t) { return program.evaluate(t); }, pieces, 8);
    for (LiftPeak* q : {&report.peaks.velocity, &report.peaks.acceleration, &report.peaks.jerk})
        q->theta = MotionProgram::wrap(q->theta);

    const std::size_t n = sites.size();
    if (n < 3) return report;
    std::vector<double> jerk(n), excursion(n);
    for (std::size_t i = 0; i < n; ++i) jerk[i] = program.evaluate(sites[i]).d3h;
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t before = (i + n - 1) % n, after = (i + 1) % n;
        const double t0 = sites[before] - (i == 0 ? two_pi : 0.0), t2 = sites[after] + (i + 1 == n ? two_pi : 0.0);
        const double w = (sites[i] - t0) / (t2 - t0);
        excursion[i] = std::abs(jerk[i] - ((1.0 - w) * jerk[before] + w * jerk[after]));
        sum += excursion[i] * excursion[i];
    }
    if (report.peaks.jerk.value > 0.0)
        report.jerk_roughness = std::sqrt(sum / static_cast<double>(n)) / report.peaks.jerk.value;
    std::vector<JerkExcursion> local;
    for (std::size_t i = 0; i < n; ++i) {
        const double e = excursion[i];
        if (e > 0.0 && e >= excursion[(i + n - 1) % n] && e >= excursion[(i + 1) % n]) local.push_back({sites[i], e});
    }
    std::sort(local.begin(), local.end(),
              [](const JerkExcursion& a, const JerkExcursion& b) { return a.excursion > b.excursion; });
    if (local.size() > excursions) local.resize(excursions);
    report.jerk_excursions = std::move(local);
    return report;
}

}  // namespace camfollower
