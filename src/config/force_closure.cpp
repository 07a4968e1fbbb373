// SPDX-License-Identifier: BSD-3-Clause
#include "force_closure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/LU>
#include <Eigen/QR>

#include "camfollower/error.hpp"

namespace camfollower::config {

namespace {

using Model = Mechanism<Eigen::Dynamic>;

// Cam angles per revolution: 0.5 deg up to 40 DOFs; fewer on large models (a static equilibrium and a
// dense solve per angle: a few ms each at 100 DOFs), never below 90 (4 deg).
int grid_size(int dofs) {
    if (dofs <= 40) return 720;
    return std::max(90, 2 * int(360.0 * 20.0 / dofs));
}

std::string number(const char* format, double v) {
    char text[48];
    std::snprintf(text, sizeof text, format, v);
    return text;
}
std::string newtons(double f) { return number("%.4g", f == 0.0 ? 0.0 : f) + " N"; }  // no "-0 N"
std::string degrees(double rad) {
    double d = std::fmod(radians_to_degrees(rad), 360.0);
    if (d < 0.0) d += 360.0;
    if (d >= 359.95) d = 0.0;
    return number("%.1f", d);
}
std::string speed(double rpm) { return number(rpm >= 100.0 ? "%.0f" : "%.3g", rpm) + " rpm"; }

// Runs of `bad` on the circular grid as (first, last) angles (rad, already shifted to cam angles).
std::vector<std::pair<double, double>> runs(const std::vector<bool>& bad, double step, double shift) {
    std::vector<std::pair<double, double>> out;
    const int n = int(bad.size());
    if (std::all_of(bad.begin(), bad.end(), [](bool b) { return b; })) return {{shift, shift + two_pi - step}};
    // Start after a good point, so a run through angle 0 stays one run.
    int start = 0;
    while (bad[std::size_t(start)]) ++start;
    for (int k = 1; k <= n; ++k) {
        const int j = (start + k) % n;
        if (!bad[std::size_t(j)]) continue;
        int last = j;
        while (bad[std::size_t((last + 1) % n)]) last = (last + 1) % n;
        out.emplace_back(shift + j * step, shift + last * step);
        k += (last - j + n) % n;
    }
    return out;
}

std::string intervals(const std::vector<std::pair<double, double>>& r, double step) {
    // Every grid point: runs() gives the one interval of length 2 pi - step.
    if (r.size() == 1 && std::abs(r[0].second - r[0].first - (two_pi - step)) < 0.5 * step)
        return "the whole revolution";
    std::string out;
    const std::size_t shown = std::min<std::size_t>(r.size(), 3);
    for (std::size_t i = 0; i < shown; ++i)
        out += (i ? ", " : "") + degrees(r[i].first) + " to " + degrees(r[i].second) + " deg";
    if (r.size() > shown) out += detail::concat(" and ", r.size() - shown, " more intervals");
    return out;
}

// The lowest omega > 0 at which c + b omega + a omega^2 (c > 0) turns negative; infinity if none.
double first_negative(double a, double b, double c) {
    const double inf = std::numeric_limits<double>::infinity();
    if (a == 0.0) return b < 0.0 ? -c / b : inf;
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0 || (a > 0.0 && b >= 0.0)) return inf;  // a > 0: positive for every omega > 0 then
    // The roots, computed without cancellation: q / a and c / q. With a < 0 one is positive (the
    // crossing); with a > 0 and b < 0 both are, and the function is negative between them.
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double lo = inf;
    for (double r : {q / a, c / q})
        if (r > 0.0 && std::isfinite(r)) lo = std::min(lo, r);
    return lo;
}

// d delta / d q_follower of a pair at shaft angle theta: its g on its follower DOF.
double follower_coefficient(const ContactPair& pair, double theta, double omega, const Eigen::VectorXd& q) {
    ContactTerms c;
    if (pair.twist() >= 0) pair.evaluate(theta + pair.spec().phase + q[pair.twist()], omega, c);
    else pair.evaluate(theta + pair.spec().phase, omega, c);
    for (int k = 0; k < c.count; ++k)
        if (c.dof[std::size_t(k)] == pair.follower()) return c.g[std::size_t(k)];
    return 0.0;
}

ForceClosure check(const Model& m, double rpm) {
    ForceClosure out;
    out.rpm = rpm;
    const int n = m.size();
    const std::size_t nc = m.contacts().size();
    const int steps = grid_size(n);
    out.angles = steps;
    if (nc == 0) return out;
    const double step = two_pi / steps, omega = m.omega();
    const std::size_t count = std::size_t(steps);

    // Conjugate cams: the partner of each contact pushing the same follower DOF the other way (-1: none).
    std::vector<int> partner(nc, -1);
    for (std::size_t i = 0; i < nc; ++i)
        for (std::size_t j = 0; j < nc; ++j) {
            const ContactPairSpec &a = m.contacts()[i].spec(), &b = m.contacts()[j].spec();
            if (i != j && a.follower_dof == b.follower_dof && a.follower_ratio * b.follower_ratio < 0.0)
                partner[i] = int(j);
        }
    // The rigid check holds one of the two (the one mapped with a positive ratio, the lift cam).
    const auto held = [&](std::size_t i) { return partner[i] < 0 || m.contacts()[i].spec().follower_ratio > 0.0; };

    std::vector<Eigen::VectorXd> q(count);
    try {
        for (int j = 0; j < steps; ++j) q[std::size_t(j)] = m.static_equilibrium(j * step);
    } catch (const std::exception& e) {
        out.warnings.push_back(detail::concat("the force-closure check could not run: ", e.what()));
        return out;
    }
    // Per contact and angle: the static force and the parts of the rigid check's force per omega and omega^2.
    std::vector<std::vector<double>> Fs(nc, std::vector<double>(count)), F1 = Fs, F2 = Fs;
    std::vector<double> preload(nc, 0.0);  // a conjugate pair's largest static force (the net's scale)
    const int size = n + int(nc);
    Eigen::MatrixXd A(size, size), rhs(size, 2);
    for (int j = 0; j < steps; ++j) {
        const double theta = j * step;
        const Eigen::VectorXd& q0 = q[std::size_t(j)];
        const Eigen::VectorXd& qm = q[std::size_t((j + steps - 1) % steps)];
        const Eigen::VectorXd& qp = q[std::size_t((j + 1) % steps)];
        const Eigen::VectorXd v = (qp - qm) / (2.0 * step), a = (qp - 2.0 * q0 + qm) / (step * step);
        A.setZero();
        A.topLeftCorner(n, n) = m.tangent_stiffness(theta, q0);
        for (std::size_t i = 0; i < nc; ++i) {
            const ContactPair& pair = m.contacts()[i];
            ContactTerms c;
            const int col = n + int(i);
            Fs[i][std::size_t(j)] = m.static_contact_force(theta, q0, i);
            if (!held(i)) {  // its partner's force says where it carries the load
                A(col, col) = 1.0;
                continue;
            }
            if (pair.twist() >= 0) {
                pair.evaluate(theta + pair.spec().phase + q0[pair.twist()], omega, c);
                double arm = c.delta0_theta;
                for (int k = 0; k < c.count; ++k) arm += c.g_theta[std::size_t(k)] * q0[c.dof[std::size_t(k)]];
                A(pair.twist(), col) += arm, A(col, pair.twist()) += arm;
            } else {
                pair.evaluate(theta + pair.spec().phase, omega, c);
            }
            for (int k = 0; k < c.count; ++k) {
                const int dof = c.dof[std::size_t(k)];
                A(dof, col) += c.g[std::size_t(k)], A(col, dof) += c.g[std::size_t(k)];
            }
        }
        rhs.setZero();
        rhs.col(0).head(n) = -(m.mass() * a);
        rhs.col(1).head(n) = -(m.damping() * v);
        Eigen::MatrixXd x = A.partialPivLu().solve(rhs);
        // A structure that holds the inertia loads only through a free clearance or the like is singular
        // there: the least-squares answer (its free motion carries no contact force).
        if (!x.allFinite() || (A * x - rhs).norm() > 1e-6 * (A.norm() * x.norm() + rhs.norm()))
            x = A.completeOrthogonalDecomposition().solve(rhs);
        for (std::size_t i = 0; i < nc; ++i)
            F2[i][std::size_t(j)] = x(n + int(i), 0), F1[i][std::size_t(j)] = x(n + int(i), 1);
        // Conjugate cams both carry the preload; the rigid check's force on the held cam is the net one,
        // the other's force taken over in the held one's terms (the ratio of their follower coefficients).
        for (std::size_t i = 0; i < nc; ++i)
            if (partner[i] >= 0 && held(i)) {
                const std::size_t k = std::size_t(partner[i]);
                const double share = follower_coefficient(m.contacts()[k], theta, omega, q0) /
                                     follower_coefficient(m.contacts()[i], theta, omega, q0);
                preload[i] = std::max({preload[i], std::abs(Fs[i][std::size_t(j)]), std::abs(Fs[k][std::size_t(j)])});
                Fs[i][std::size_t(j)] += share * Fs[k][std::size_t(j)];
            }
    }

    const double max_rpm = detail::max_camshaft_speed * 30.0 / pi;
    for (std::size_t i = 0; i < nc; ++i) {
        const ContactPair& pair = m.contacts()[i];
        const double phase = pair.spec().phase;
        ContactClosure r;
        r.contact = pair.name();
        double scale = 0.0;
        for (double f : Fs[i]) scale = std::max(scale, std::abs(f));
        const double tol = 1e-9 * (scale + 1.0);
        std::vector<bool> open(count), lost(count);
        double limit = std::numeric_limits<double>::infinity();
        std::size_t smin = 0, rmin = 0;
        std::vector<double> F(count);
        for (std::size_t j = 0; j < count; ++j) {
            F[j] = Fs[i][j] + omega * F1[i][j] + omega * omega * F2[i][j];
            open[j] = Fs[i][j] <= tol;
            lost[j] = F[j] < -tol;
            if (Fs[i][j] < Fs[i][smin]) smin = j;
            if (F[j] < F[rmin]) rmin = j;
            limit = std::min(limit, open[j] ? 0.0 : first_negative(F2[i][j], F1[i][j], Fs[i][j]));
        }
        r.static_min_force = Fs[i][smin], r.static_min_angle = std::fmod(double(smin) * step + phase, two_pi);
        r.rigid_min_force = F[rmin], r.rigid_min_angle = std::fmod(double(rmin) * step + phase, two_pi);
        r.rigid_limit_rpm = limit * 30.0 / pi > max_rpm ? std::numeric_limits<double>::infinity() : limit * 30.0 / pi;
        const std::string who = "contact '" + detail::printable(r.contact) + "'";
        if (partner[i] >= 0) {
            // Form-closed: the held cam's net force, where < 0, is on the other cam. The net is a difference
            // of preloads: zero in a dwell to the static equilibrium's accuracy, so judged against them.
            const std::size_t h = held(i) ? i : std::size_t(partner[i]);
            const double net_tol = 1e-6 * (preload[h] + 1.0);
            std::vector<bool> other(count);
            std::vector<int> carrier;  // +1 the held cam, -1 the other, in order; where the net force is ~0
            for (std::size_t j = 0; j < count; ++j) {  // (a dwell, only the preload) neither counts
                const double net = Fs[h][j] + omega * F1[h][j] + omega * omega * F2[h][j];
                other[j] = held(i) ? net < -net_tol : net > net_tol;
                if (std::abs(net) > net_tol) carrier.push_back(net > 0.0 ? 1 : -1);
            }
            r.conjugate = m.contacts()[std::size_t(partner[i])].name();
            r.other_cam = runs(other, step, phase);
            for (std::size_t j = 0; j < carrier.size(); ++j)
                r.flank_changes += carrier[j] != carrier[(j + 1) % carrier.size()] ? 1 : 0;
            r.rigid_loss.clear();
        } else if (pair.grooved()) {
            r.grooved = true;
            r.outer_flank = runs(lost, step, phase);
            for (std::size_t j = 0; j < count; ++j) r.flank_changes += lost[j] != lost[(j + 1) % count] ? 1 : 0;
        } else if (std::find(open.begin(), open.end(), true) != open.end()) {
            r.static_open = runs(open, step, phase);
            out.warnings.push_back(detail::concat(
                who, " is not force-closed: at rest its contact force is <= 0 (", newtons(r.static_min_force),
                " at cam angle ", degrees(r.static_min_angle), " deg; over ", intervals(r.static_open, step),
                "): nothing presses the follower onto the cam there; add a return spring with a preload, or a load, "
                "that holds it on the cam"));
        } else if (std::find(lost.begin(), lost.end(), true) != lost.end()) {
            r.rigid_loss = runs(lost, step, phase);
            out.warnings.push_back(detail::concat(
                who, " is not force-closed at ", speed(rpm),
                ": in the rigid check (the mechanism following the cam "
                "quasi-statically: springs, preloads and loads against its inertia and damping) the contact force "
                "falls to ",
                newtons(r.rigid_min_force), " at cam angle ", degrees(r.rigid_min_angle), " deg, below zero over ",
                intervals(r.rigid_loss, step), "; the check keeps contact up to ", speed(r.rigid_limit_rpm),
                " (raise the return spring's preload or rate, or lower the speed)"));
        }
        out.contacts.push_back(std::move(r));
    }
    return out;
}

}  // namespace

ForceClosure check_force_closure(const MechanismBuilder& b, double rpm) {
    if (rpm <= 0.0) return check(Model(b), b.camshaft_speed_rpm());
    MechanismBuilder at = b;
    at.set_camshaft_speed_rpm(rpm);
    return check(Model(at), rpm);
}

}  // namespace camfollower::config
