// SPDX-License-Identifier: BSD-3-Clause
// Fox-Goodwin under a tolerance unless the run meets a contact event, DOP853 when it does
// (Method::fox_goodwin_or_dop853, what method "auto" takes under a tolerance where the model's fastest
// modes ring; solver/choose_method.hpp).
//
// Why two methods: without contact loss Fox-Goodwin under a tolerance is the cheapest way to a given
// accuracy in force on the cam models measured (docs/benchmarks.md), but Newmark does not end a step at
// an event, so across the kinks of a contact loss it is second order and its steps crowd there
// (3-9x DOP853's time). Whether a run loses contact cannot be told at its start. So Fox-Goodwin runs
// until it sees a contact event (or cannot meet the tolerance at its finest step); then the whole run
// is done again from its start by DOP853 (simulate(), periodic_orbit()), which locates the events and
// ends its steps there. Again from the start, not on from the event: the error Fox-Goodwin leaves
// before a loss (1e-9 of the peak force at tolerance 1e-8, DOP853's 3e-12) is amplified some 1000x
// by the landing after the flight, a steep impact.
#pragma once

#include <exception>

#include "camfollower/error.hpp"
#include "camfollower/solver/newmark.hpp"

namespace camfollower {

// The settings of each of the two methods, from those of the pair.
inline NewmarkSettings fox_goodwin_part(NewmarkSettings s) {
    s.method = Method::newmark_adaptive;
    return s;
}
inline NewmarkSettings dop853_part(NewmarkSettings s) {
    s.method = Method::dop853;
    return s;
}

namespace detail {
// Thrown by FoxGoodwinUnlessEvents at the first contact event: the run goes to DOP853.
struct FoxGoodwinGaveWay : std::exception {
    double time = 0.0;      // start of the output interval in which Fox-Goodwin gave way
    SolverStatistics work;  // Fox-Goodwin's, until then
    const char* what() const noexcept override { return "Fox-Goodwin met a contact event: the run goes to DOP853"; }
};
}  // namespace detail

// Fox-Goodwin under the settings' tolerance; throws detail::FoxGoodwinGaveWay from step() at the end of
// the first output interval in which it saw a contact event, or in which it could not meet the
// tolerance at its finest step.
template <class System>
class FoxGoodwinUnlessEvents {
public:
    using Vector = typename System::Vector;
    using StateType = State<System>;

    FoxGoodwinUnlessEvents(const System& system, const NewmarkSettings& settings)
        : s_(validated(settings)), fox_goodwin_(system, fox_goodwin_part(s_)) {}
    FoxGoodwinUnlessEvents(System&&, const NewmarkSettings&) = delete;

    const NewmarkSettings& settings() const { return s_; }
    const System& system() const { return fox_goodwin_.system(); }
    double time_step() const { return s_.time_step; }  // the output interval
    double force_scale() const { return fox_goodwin_.force_scale(); }
    StateType start(double t, const Vector& q, const Vector& v) { return fox_goodwin_.start(t, q, v); }

    void step(StateType& s, SolverStatistics& stats) {
        const double t0 = s.t;
        try {
            fox_goodwin_.step(s, stats);
        } catch (const ConvergenceError&) {  // the tolerance not met at the finest step
            give_way(t0, stats);
        }
        if (!fox_goodwin_.events().empty()) give_way(t0, stats);
    }

    void set_interrupt(std::function<bool()> keep_going) { fox_goodwin_.set_interrupt(std::move(keep_going)); }
    const std::vector<Event>& events() const { return fox_goodwin_.events(); }  // empty: it gives way at the first
    std::vector<Event> take_events() { return fox_goodwin_.take_events(); }
    double highest_angular_frequency(const StateType& s) { return fox_goodwin_.highest_angular_frequency(s); }

private:
    static NewmarkSettings validated(const NewmarkSettings& s) {
        s.validate();
        if (s.method != Method::fox_goodwin_or_dop853)
            detail::fail("FoxGoodwinUnlessEvents needs method fox_goodwin_or_dop853, got '", method_name(s), "'");
        return s;
    }
    [[noreturn]] static void give_way(double t, const SolverStatistics& stats) {
        detail::FoxGoodwinGaveWay e;
        e.time = t, e.work = stats;
        throw e;
    }

    NewmarkSettings s_;
    Newmark<System> fox_goodwin_;
};

}  // namespace camfollower
