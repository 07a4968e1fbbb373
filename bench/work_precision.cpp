// SPDX-License-Identifier: BSD-3-Clause
// Work against precision on what users read: the contact force and the follower acceleration of the
// paper preset over one revolution, for each camfollower method and setting, and (when installed)
// boost::numeric::odeint's dopri5 and fehlberg78 and SUNDIALS' CVODE (BDF, Adams) and ARKODE ERK
// (orders 5 and 8) driving the same model evaluation.
//   cmake -S . -B build-bench -DCAMFOLLOWER_BUILD_BENCHMARKS=ON && cmake --build build-bench
//   build-bench/bench/camfollower_work_precision [--stiff] [--rpm N] [--repeats N]
// The contact-loss case is --rpm 2000 (above the preset's jump speed, 1329 rpm): camfollower's runs
// report the contact losses and re-contacts they located, the reference the sign changes of its
// penetration on the output grid.
// Each setting runs `repeats` times, interleaved with the others; the CPU time reported is the median.
// Errors: max |x - x_ref| / max |x_ref| over the output grid (2048 rows per revolution); the reference
// is odeint's fehlberg78 on a long double state at rtol 1e-13 when Boost is available (restarted at each
// contact event when the contact opens: run_reference), checked against itself at rtol 1e-15, else
// Dormand-Prince at tolerance 1e-12.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate.hpp"
#include "tight_newmark.hpp"

#if CAMFOLLOWER_HAVE_ODEINT
#include <boost/numeric/odeint.hpp>
#endif
#if CAMFOLLOWER_HAVE_SUNDIALS
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>
#endif

namespace cf = camfollower;
using Model = cf::Mechanism<cf::presets::paper_dofs>;

namespace {

constexpr int grid = 2048;   // output rows per revolution
constexpr int follower = 3;  // y4, the follower's DOF

// The channels compared: contact force and follower acceleration on the output grid.
struct Histories {
    std::vector<double> force, accel, gap;  // gap: the contact's penetration (m)
    double cpu_ms = 0.0;
    long events = -1;  // located contact losses and re-contacts (-1: the method does not locate them)
    std::uint64_t steps = 0, evaluations = 0;
};

double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

Histories run_camfollower(const Model& m, const cf::SolverSettings& s) {
    cf::RunOptions o;
    o.duration = m.period();
    const double dt = m.period() / grid;
    o.record.decimation = std::size_t(std::llround(dt / s.time_step));
    const double t0 = cpu_seconds();
    const auto r = cf::simulate(m, s, o);
    Histories h;
    h.cpu_ms = 1e3 * (cpu_seconds() - t0);
    const double* f = r.recording.channel("cam.force");
    const double* a = r.recording.channel(r.recording.block(2) + follower);
    h.force.assign(f, f + r.recording.rows);
    h.accel.assign(a, a + r.recording.rows);
    const double* g = r.recording.channel("cam.penetration");
    h.gap.assign(g, g + r.recording.rows);
    h.events = long(r.events.size());
    h.steps = r.report.stats.steps;
    h.evaluations = r.report.stats.evaluations;
    return h;
}

using Y = std::array<double, 2 * cf::presets::paper_dofs>;
// The reference integrates in long double: over the millions of steps of rtol 1e-13, rounding the
// double state (~1e-18 m on a 1e-2 m coordinate, times the contact stiffness) drives the lightly damped
// contact mode by a random walk: a double reference at 1e-13 is itself off by 1e-6 in force with the
// contact stiffness x100 (against 4e-9 for a long double one; docs/benchmarks.md).
using YL = std::array<long double, 2 * cf::presets::paper_dofs>;

// y' = (v, M^-1 (-(C v + K q + f))) through the system contract: the same evaluation camfollower uses.
struct Rhs {
    const Model& m;
    Model::Matrix M_inv;
    mutable Model::Workspace ws;
    mutable std::uint64_t evaluations = 0;
    explicit Rhs(const Model& model) : m(model), M_inv(model.mass().inverse()), ws(model.workspace()) {}
    void acceleration(double t, const Model::Vector& q, const Model::Vector& v, Model::Vector& a) const {
        Model::Vector f;
        m.prepare(t, ws);
        m.force(ws, q, v, f);
        a = -(M_inv * (m.damping() * v + m.stiffness() * q + f));
        ++evaluations;
    }
    void operator()(const Y& y, Y& dy, double t) const {
        Model::Vector q, v, a;
        for (int i = 0; i < 7; ++i) q[i] = y[std::size_t(i)], v[i] = y[std::size_t(7 + i)];
        acceleration(t, q, v, a);
        for (int i = 0; i < 7; ++i) dy[std::size_t(i)] = v[i], dy[std::size_t(7 + i)] = a[i];
    }
    // The reference's long double state, the model's double evaluation.
    void operator()(const YL& y, YL& dy, long double t) const {
        Y yd, dyd;
        for (std::size_t i = 0; i < y.size(); ++i) yd[i] = double(y[i]);
        (*this)(yd, dyd, double(t));
        for (std::size_t i = 0; i < y.size(); ++i) dy[i] = dyd[i];
    }
};

// Observer on the grid: contact force (the model's channel) and follower acceleration at each row.
struct GridObserver {
    const Rhs& rhs;
    Histories& h;
    void operator()(const Y& y, double t) const {
        Model::Vector q, v, a;
        for (int i = 0; i < 7; ++i) q[i] = y[std::size_t(i)], v[i] = y[std::size_t(7 + i)];
        rhs.acceleration(t, q, v, a);
        std::vector<double> out(rhs.m.channel_names().size());
        rhs.m.observe(rhs.ws, q, v, out.data());
        h.force.push_back(out[force_channel(rhs.m)]);
        h.gap.push_back(out[force_channel(rhs.m) + 1]);  // cam.penetration follows cam.force
        h.accel.push_back(a[follower]);
    }
    void operator()(const YL& y, long double t) const {
        Y yd;
        for (std::size_t i = 0; i < y.size(); ++i) yd[i] = double(y[i]);
        (*this)(yd, double(t));
    }
    static std::size_t force_channel(const Model& m) {
        const auto names = m.channel_names();
        return std::size_t(std::find(names.begin(), names.end(), "cam.force") - names.begin());
    }
};

// The hand-written tight Newmark (tight_newmark.hpp) on the same model evaluation: the yardstick of
// camfollower's per-step overhead (same scheme, same states), not a peer.
Histories run_tight(const Model& m, long steps, double beta) {
    const long decimation = steps / grid;
    bench::TightNewmark<Model> stepper(m, m.period() / double(steps), beta);
    std::vector<double> out(m.channel_names().size());
    const std::size_t force = GridObserver::force_channel(m);
    Histories h;
    h.force.reserve(grid + 1), h.accel.reserve(grid + 1), h.gap.reserve(grid + 1);
    const double t0 = cpu_seconds();
    auto record = [&] {
        m.observe(stepper.workspace(), stepper.q(), stepper.v(), out.data());
        h.force.push_back(out[force]);
        h.gap.push_back(out[force + 1]);
        h.accel.push_back(stepper.a()[follower]);
    };
    stepper.start(0.0, m.initial_displacement(), Model::Vector::Zero());
    record();
    for (long n = 1; n <= steps; ++n) {
        if (!stepper.step()) throw std::runtime_error("tight Newmark: Newton did not converge");
        if (n % decimation == 0) record();
    }
    h.cpu_ms = 1e3 * (cpu_seconds() - t0);
    h.steps = std::uint64_t(steps);
    return h;
}

// Absolute tolerance of the peers: at the scale of the smallest meaningful displacement (1e-3 of the
// 10 mm lift).
double peer_atol(double rtol) { return rtol * 1e-5; }

#if CAMFOLLOWER_HAVE_ODEINT
Histories run_odeint(const Model& m, const std::string& method, double tol) {
    namespace odeint = boost::numeric::odeint;
    Rhs rhs(m);
    Y y{};
    const Model::Vector q0 = m.initial_displacement();
    for (int i = 0; i < 7; ++i) y[std::size_t(i)] = q0[i];
    std::vector<double> times(grid + 1);
    for (int i = 0; i <= grid; ++i) times[std::size_t(i)] = m.period() * i / grid;
    Histories h;
    h.force.reserve(grid + 1), h.accel.reserve(grid + 1);
    GridObserver obs{rhs, h};
    const double t0 = cpu_seconds();
    const double atol = peer_atol(tol);
    if (method == "dopri5") {
        h.steps =
            odeint::integrate_times(odeint::make_dense_output(atol, tol, odeint::runge_kutta_dopri5<Y>()),
                                    std::ref(rhs), y, times.begin(), times.end(), m.period() / grid, std::ref(obs));
    } else {
        h.steps =
            odeint::integrate_times(odeint::make_controlled(atol, tol, odeint::runge_kutta_fehlberg78<Y>()),
                                    std::ref(rhs), y, times.begin(), times.end(), m.period() / grid, std::ref(obs));
    }
    h.cpu_ms = 1e3 * (cpu_seconds() - t0);
    h.evaluations = rhs.evaluations;
    return h;
}

// The reference when the contact opens and closes: fehlberg78 restarted at each contact event (the
// kinks of the force), so that no step straddles one; the event times are camfollower's, located at
// Dormand-Prince tolerance 1e-12, and checked here: the penetration of this solution at each must be
// ~0 (printed). Without the restarts a controlled step across a kink leaves ~1e-7 behind.
Histories run_reference(const Model& m, double tol, const std::vector<double>& breaks) {
    namespace odeint = boost::numeric::odeint;
    Rhs rhs(m);
    YL y{};
    const Model::Vector q0 = m.initial_displacement();
    for (int i = 0; i < 7; ++i) y[std::size_t(i)] = q0[i];
    Histories h;
    GridObserver obs{rhs, h};
    const double T = m.period();
    std::vector<double> ends = breaks;
    ends.push_back(T);
    double start = 0.0, worst_gap = 0.0;
    int next_row = 0;
    for (const double end : ends) {
        // This piece's output rows, with its start and end as the first and last times.
        std::vector<long double> times{start};
        const int first_row = next_row;
        while (next_row <= grid && T * next_row / grid <= end) times.push_back(T * next_row++ / grid);
        if (times.back() != end) times.push_back(end);
        int wanted = first_row;  // the next row to record (the start may repeat a row's time)
        auto record = [&](const YL& state, long double t) {
            if (wanted < next_row && double(t) == T * wanted / grid) obs(state, t), ++wanted;
        };
        using Stepper = odeint::runge_kutta_fehlberg78<YL, long double, YL, long double>;
        odeint::integrate_times(odeint::make_controlled((long double)peer_atol(tol), (long double)tol, Stepper()),
                                std::ref(rhs), y, times.begin(), times.end(), (long double)(T / grid), record);
        if (end < T) {
            Model::Vector q, v, f;
            for (int i = 0; i < 7; ++i) q[i] = double(y[std::size_t(i)]), v[i] = double(y[std::size_t(7 + i)]);
            m.prepare(end, rhs.ws);
            m.force(rhs.ws, q, v, f);
            double gap[1];
            m.event_values(rhs.ws, q, v, gap);
            worst_gap = std::max(worst_gap, std::abs(gap[0]));
        }
        start = end;
    }
    if (!breaks.empty())
        std::printf("# reference: %zu restarts at contact events, largest |penetration| there %.2e m\n", breaks.size(),
                    worst_gap);
    h.evaluations = rhs.evaluations;
    return h;
}
#endif

#if CAMFOLLOWER_HAVE_SUNDIALS
// SUNDIALS 6 on the same right-hand side: CVODE (BDF with Newton and a dense Jacobian by differences;
// Adams with fixed-point iteration) and ARKODE's explicit ERKStep (order 5: Dormand-Prince 7-4-5,
// order 8: Fehlberg 13-7-8), each interpolating to the output grid (CV_NORMAL / ARK_NORMAL).
int sundials_rhs(sunrealtype t, N_Vector y, N_Vector dy, void* user) {
    const Rhs& rhs = *static_cast<const Rhs*>(user);
    Y in, out;
    std::copy(N_VGetArrayPointer(y), N_VGetArrayPointer(y) + in.size(), in.begin());
    rhs(in, out, t);
    std::copy(out.begin(), out.end(), N_VGetArrayPointer(dy));
    return 0;
}

Histories run_sundials(const Model& m, const std::string& method, double tol) {
    Rhs rhs(m);
    SUNContext ctx = nullptr;
    if (SUNContext_Create(nullptr, &ctx) != 0) throw std::runtime_error("SUNContext_Create failed");
    N_Vector y = N_VNew_Serial(sunindextype(Y().size()), ctx);
    N_VConst(0.0, y);
    const Model::Vector q0 = m.initial_displacement();
    for (int i = 0; i < 7; ++i) N_VGetArrayPointer(y)[i] = q0[i];
    Histories h;
    h.force.reserve(grid + 1), h.accel.reserve(grid + 1);
    GridObserver obs{rhs, h};
    const auto observe = [&](double t) {
        Y state;
        std::copy(N_VGetArrayPointer(y), N_VGetArrayPointer(y) + state.size(), state.begin());
        obs(state, t);
    };
    const double t0 = cpu_seconds();
    observe(0.0);
    long steps = 0;
    const bool erk = method == "erk5" || method == "erk8";
    void* mem = nullptr;
    SUNMatrix A = nullptr;
    SUNLinearSolver LS = nullptr;
    SUNNonlinearSolver NLS = nullptr;
    bool ok = true;
    if (erk) {
        mem = ERKStepCreate(sundials_rhs, 0.0, y, ctx);
        ok = ERKStepSStolerances(mem, tol, peer_atol(tol)) == 0 && ERKStepSetUserData(mem, &rhs) == 0 &&
             ERKStepSetTableNum(mem, method == "erk5" ? ARKODE_DORMAND_PRINCE_7_4_5 : ARKODE_FEHLBERG_13_7_8) == 0 &&
             ERKStepSetMaxNumSteps(mem, 100000000) == 0;
    } else {
        mem = CVodeCreate(method == "bdf" ? CV_BDF : CV_ADAMS, ctx);
        ok = CVodeInit(mem, sundials_rhs, 0.0, y) == 0 && CVodeSStolerances(mem, tol, peer_atol(tol)) == 0 &&
             CVodeSetUserData(mem, &rhs) == 0 && CVodeSetMaxNumSteps(mem, 100000000) == 0;
        if (method == "bdf") {
            A = SUNDenseMatrix(sunindextype(Y().size()), sunindextype(Y().size()), ctx);
            LS = SUNLinSol_Dense(y, A, ctx);
            ok = ok && CVodeSetLinearSolver(mem, LS, A) == 0;
        } else {
            NLS = SUNNonlinSol_FixedPoint(y, 0, ctx);
            ok = ok && CVodeSetNonlinearSolver(mem, NLS) == 0;
        }
    }
    for (int i = 1; ok && i <= grid; ++i) {
        const double t_out = m.period() * i / grid;
        double t = 0.0;
        ok = (erk ? ERKStepEvolve(mem, t_out, y, &t, ARK_NORMAL) : CVode(mem, t_out, y, &t, CV_NORMAL)) >= 0;
        if (ok) observe(t);
    }
    if (erk) {
        ERKStepGetNumSteps(mem, &steps);
        ERKStepFree(&mem);
    } else {
        CVodeGetNumSteps(mem, &steps);
        CVodeFree(&mem);
    }
    h.cpu_ms = 1e3 * (cpu_seconds() - t0);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    if (NLS) SUNNonlinSolFree(NLS);
    N_VDestroy(y);
    SUNContext_Free(&ctx);
    h.steps = std::uint64_t(steps);
    h.evaluations = rhs.evaluations;
    if (!ok) h.force.clear(), h.accel.clear();  // failed: reported with an infinite error
    return h;
}
#endif

struct Setting {
    std::string label;
    std::function<Histories()> run;
    std::vector<double> times;
    Histories last;
};

double relative_error(const std::vector<double>& x, const std::vector<double>& ref) {
    double err = 0.0, peak = 0.0;
    for (std::size_t i = 0; i < ref.size() && i < x.size(); ++i) {
        err = std::max(err, std::abs(x[i] - ref[i]));
        peak = std::max(peak, std::abs(ref[i]));
    }
    return x.size() == ref.size() ? err / peak : INFINITY;
}

// Sign changes of the penetration on the output grid: the contact losses and re-contacts a run shows.
long sign_changes(const std::vector<double>& gap) {
    long n = 0;
    for (std::size_t i = 1; i < gap.size(); ++i) n += (gap[i] > 0.0) != (gap[i - 1] > 0.0);
    return n;
}

}  // namespace

int main(int argc, char** argv) {
    bool stiff = false;
    double rpm = 750.0;
    int repeats = 5;
    std::string only;  // empty: every row
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--stiff")) stiff = true;
        else if (!std::strcmp(argv[i], "--rpm") && i + 1 < argc) rpm = std::atof(argv[++i]);
        else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else {
            std::fprintf(stderr,
                         "usage: %s [--stiff] [--rpm N] [--repeats N] [--only TEXT]\n"
                         "  --only TEXT: run the rows whose label contains TEXT, or any of its comma-separated parts\n"
                         "               (e.g. dop853, or \"radau,fox_goodwin T/2^15\")\n",
                         argv[0]);
            return 2;
        }
    }
    if (repeats < 1 || !(rpm > 0.0)) {
        std::fprintf(stderr, "--repeats must be >= 1 and --rpm > 0\n");
        return 2;
    }
    cf::CamFollowerParameters p;
    p.camshaft_speed_rpm = rpm;
    if (stiff) p.contact_stiffness *= 100.0;
    const Model m = cf::presets::paper(p);
    const double T = m.period();

    std::vector<Setting> settings;
    // Fixed steps: 2^k and 1.5 x 2^k per revolution (a step size between the powers of two).
    for (int k : {13, 14, 15, 16, 17, 18}) {
        for (const long steps : {1L << k, 3L << (k - 1)}) {
            if (steps > (1L << 18)) continue;
            const std::string per = steps == (1L << k) ? "T/2^" + std::to_string(k) : "T/" + std::to_string(steps);
            for (const char* method : {"newmark", "fox_goodwin"}) {
                cf::SolverSettings s;
                s.time_step = T / double(steps);
                s.method = cf::method_from_name(method);
                try {
                    cf::Newmark<Model> probe(m, s);
                    (void)probe.start(0.0, m.initial_displacement(), Model::Vector::Zero());
                } catch (const std::exception&) {
                    continue;  // beyond the stability limit
                }
                settings.push_back(
                    {std::string(method) + " " + per, [&m, s] { return run_camfollower(m, s); }, {}, {}});
                // (not on the stiff variant: without camfollower's rounding floor of the residual its
                // Newton iteration stalls there at the tolerance)
                if (s.method == cf::Method::fox_goodwin && !stiff)
                    settings.push_back({"hand tight_newmark fox_goodwin " + per,
                                        [&m, steps] { return run_tight(m, steps, 1.0 / 12.0); },
                                        {},
                                        {}});
            }
        }
    }
    for (const char* method : {"dormand_prince", "dop853", "radau"})
        for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12}) {
            cf::SolverSettings s;
            s.method = cf::method_from_name(method);
            s.tolerance = tol;
            s.time_step = T / grid;
            char label[64];
            std::snprintf(label, sizeof label, "%s tol %.0e", method, tol);
            settings.push_back({label, [&m, s] { return run_camfollower(m, s); }, {}, {}});
        }
    // Newmark under a tolerance: steps of T / 2048 / 2^level, the level by the error estimate.
    for (const char* method : {"newmark", "fox_goodwin"})
        for (double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
            cf::SolverSettings s;
            s.method = cf::method_from_name(method);
            s.time_step = T / grid;
            s.tolerance = tol;
            s.max_halvings = 12;
            char label[64];
            std::snprintf(label, sizeof label, "%s tol %.0e", method, tol);
            settings.push_back({label, [&m, s] { return run_camfollower(m, s); }, {}, {}});
        }
    // Method "auto" under a tolerance, labelled with the method it takes on this model.
    for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11}) {
        cf::SolverSettings s;
        s.method = cf::method_from_name("auto");
        s.time_step = T / grid;
        s.tolerance = tol;
        const cf::SolverSettings chosen = cf::concrete_settings(m, s, std::nullopt, std::nullopt).settings;
        char label[64];
        std::snprintf(label, sizeof label, "auto tol %.0e (%s)", tol, cf::method_name(chosen.method));
        settings.push_back({label, [&m, s] { return run_camfollower(m, s); }, {}, {}});
    }
    // The peers: (library, method, its runner) at four tolerances each.
    struct Peer {
        const char* library;
        const char* method;
        Histories (*run)(const Model&, const std::string&, double);
    };
    std::vector<Peer> peers;
#if CAMFOLLOWER_HAVE_ODEINT
    for (const char* method : {"dopri5", "fehlberg78"}) peers.push_back({"odeint", method, run_odeint});
#endif
#if CAMFOLLOWER_HAVE_SUNDIALS
    for (const char* method : {"bdf", "adams", "erk5", "erk8"}) peers.push_back({"SUNDIALS", method, run_sundials});
#endif
    for (const Peer& peer : peers)
        for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
            char label[64];
            std::snprintf(label, sizeof label, "%s %s rtol %.0e", peer.library, peer.method, tol);
            settings.push_back({label, [&m, peer, tol] { return peer.run(m, peer.method, tol); }, {}, {}});
        }
    settings.erase(std::remove_if(settings.begin(), settings.end(),
                                  [&only](const Setting& s) {
                                      // Any of the comma-separated parts of TEXT.
                                      for (std::size_t from = 0; from <= only.size();) {
                                          const std::size_t comma = std::min(only.find(',', from), only.size());
                                          if (s.label.find(only.substr(from, comma - from)) != std::string::npos)
                                              return false;
                                          from = comma + 1;
                                      }
                                      return true;
                                  }),
                   settings.end());
#if CAMFOLLOWER_HAVE_ODEINT
    // Where the contact opens and closes, the reference restarts at each event (run_odeint_piecewise).
    std::vector<double> breaks;
    {
        cf::SolverSettings es;
        es.method = cf::method_from_name("dormand_prince");
        es.tolerance = 1e-12;
        es.time_step = T / grid;
        cf::RunOptions eo;
        eo.duration = T;
        for (const cf::Event& e : cf::simulate(m, es, eo).events) breaks.push_back(e.time);
    }
    const Histories ref = run_reference(m, 1e-13, breaks);
    // Its own accuracy: the same at rtol 1e-15 (printed; the floor below which errors mean nothing).
    const Histories ref_check = run_reference(m, 1e-15, breaks);
    std::printf("# the reference against itself at rtol 1e-15: force %.1e, follower acceleration %.1e\n",
                relative_error(ref.force, ref_check.force), relative_error(ref.accel, ref_check.accel));
    const char* ref_name = breaks.empty()
                               ? "odeint fehlberg78 in long double at rtol 1e-13"
                               : "odeint fehlberg78 in long double at rtol 1e-13, restarted at each contact event";
#else
    cf::SolverSettings rs;
    rs.method = cf::method_from_name("dormand_prince");
    rs.tolerance = 1e-12;
    rs.time_step = T / grid;
    const Histories ref = run_camfollower(m, rs);
    const char* ref_name = "camfollower dormand_prince at tolerance 1e-12 (Boost not found)";
#endif
    for (int r = 0; r < repeats; ++r)
        for (Setting& s : settings) {
            s.last = s.run();
            s.times.push_back(s.last.cpu_ms);
        }
    std::printf(
        "# paper preset%s, %.0f rpm, one revolution, %d output rows; reference: %s (%ld contact losses and "
        "re-contacts on its grid); median CPU time of %d\n",
        stiff ? " with contact stiffness x100" : "", rpm, grid, ref_name, sign_changes(ref.gap), repeats);
    std::printf(
        "| method | CPU ms | force error | follower accel. error | steps | force evaluations | events located |\n"
        "|---|---|---|---|---|---|---|\n");
    for (Setting& s : settings) {
        std::sort(s.times.begin(), s.times.end());
        const std::string events = s.last.events < 0 ? "-" : std::to_string(s.last.events);
        std::printf("| %s | %.2f | %.2e | %.2e | %llu | %llu | %s |\n", s.label.c_str(), s.times[s.times.size() / 2],
                    relative_error(s.last.force, ref.force), relative_error(s.last.accel, ref.accel),
                    static_cast<unsigned long long>(s.last.steps), static_cast<unsigned long long>(s.last.evaluations),
                    events.c_str());
    }
    // The fastest run reaching each target in both channels: camfollower's (any setting), `auto`'s
    // under a tolerance, and the peers'; and the ratios.
    std::printf(
        "\n| target (force and accel.) | camfollower | auto | fastest peer | peer / camfollower | peer / auto |\n"
        "|---|---|---|---|---|---|\n");
    for (double target : {1e-4, 1e-6, 1e-8}) {
        const Setting* best[3] = {nullptr, nullptr, nullptr};  // camfollower, auto, peer
        double best_ms[3] = {INFINITY, INFINITY, INFINITY};
        for (const Setting& s : settings) {
            if (!(relative_error(s.last.force, ref.force) <= target &&
                  relative_error(s.last.accel, ref.accel) <= target))
                continue;
            if (s.label.rfind("hand", 0) == 0) continue;  // the yardstick, neither camfollower nor a peer
            const bool peer = s.label.rfind("odeint", 0) == 0 || s.label.rfind("SUNDIALS", 0) == 0;
            const double ms = s.times[s.times.size() / 2];
            for (int k : {peer ? 2 : 0, s.label.rfind("auto", 0) == 0 ? 1 : -1})
                if (k >= 0 && ms < best_ms[k]) best_ms[k] = ms, best[k] = &s;
        }
        char cells[3][96], ratios[2][16];
        for (int k = 0; k < 3; ++k) {
            if (best[k]) std::snprintf(cells[k], sizeof cells[k], "%s: %.2f ms", best[k]->label.c_str(), best_ms[k]);
            else std::snprintf(cells[k], sizeof cells[k], "not reached");
        }
        for (int k = 0; k < 2; ++k) {
            if (best[k] && best[2]) std::snprintf(ratios[k], sizeof ratios[k], "%.2f", best_ms[2] / best_ms[k]);
            else std::snprintf(ratios[k], sizeof ratios[k], "-");
        }
        std::printf("| <= %.0e | %s | %s | %s | %s | %s |\n", target, cells[0], cells[1], cells[2], ratios[0],
                    ratios[1]);
    }
    return 0;
}
