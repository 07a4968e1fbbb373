// SPDX-License-Identifier: BSD-3-Clause
// Fox-Goodwin under a tolerance until the first contact event, DOP853 from there on
// (Method::fox_goodwin_then_dop853, what method "auto" takes under a tolerance when the model's
// fastest modes ring; solver/choose_method.hpp).
//
// Why two methods: without contact loss Fox-Goodwin under a tolerance is the cheapest way to a given
// accuracy in force on the cam models measured (docs/benchmarks.md), but Newmark does not end a step at
// an event, so across the kink of a contact loss it is second order and loses 3-9x to DOP853, which
// does. Whether a run loses contact cannot be told at its start. So Fox-Goodwin runs each output
// interval from a copy of the state at its start; the first interval in which it sees a contact event
// (or cannot meet the tolerance at its finest step) is run again from that copy by DOP853, which
// locates the event, ends a step there and keeps the run from then on.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "camfollower/error.hpp"
#include "camfollower/solver/dormand_prince.hpp"
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

template <class System>
class FoxGoodwinThenDop853 {
public:
    using Vector = typename System::Vector;
    using StateType = State<System>;

    FoxGoodwinThenDop853(const System& system, const NewmarkSettings& settings)
        : s_(validated(settings)), first_(system, fox_goodwin_part(s_)), then_(system, dop853_part(s_)) {}
    FoxGoodwinThenDop853(System&&, const NewmarkSettings&) = delete;

    const NewmarkSettings& settings() const { return s_; }
    const System& system() const { return first_.system(); }
    double time_step() const { return s_.time_step; }  // the output interval
    double force_scale() const { return first_.force_scale(); }

    StateType start(double t, const Vector& q, const Vector& v) {
        handed_over_ = false;
        handover_time_ = std::numeric_limits<double>::quiet_NaN();
        StateType s = first_.start(t, q, v);
        interval_start_ = s;  // sized once: the copies in step() reuse its storage
        return s;
    }

    void step(StateType& s, SolverStatistics& stats) {
        if (handed_over_) return then_.step(s, stats);
        interval_start_ = s;
        bool refused = false;
        try {
            first_.step(s, stats);
        } catch (const ConvergenceError&) {  // the tolerance not met at the finest step: DOP853's turn
            refused = true;
        }
        if (!refused && first_.events().empty()) return;
        handed_over_ = true;
        handover_time_ = interval_start_.t;
        (void)first_.take_events();  // located on Newmark's cubic; DOP853 locates them again
        const double end = interval_start_.t + s_.time_step;
        s = then_.start(interval_start_.t, interval_start_.q, interval_start_.v);
        then_.step(s, stats);
        s.t = end;
    }

    // True once DOP853 has taken over; handover_time() is then the start of the output interval it
    // took over at (NaN before).
    bool handed_over() const { return handed_over_; }
    double handover_time() const { return handover_time_; }

    const std::vector<Event>& events() const { return handed_over_ ? then_.events() : first_.events(); }
    std::vector<Event> take_events() { return handed_over_ ? then_.take_events() : first_.take_events(); }
    double highest_angular_frequency(const StateType& s) { return first_.highest_angular_frequency(s); }

private:
    static NewmarkSettings validated(const NewmarkSettings& s) {
        s.validate();
        if (s.method != Method::fox_goodwin_then_dop853)
            detail::fail("FoxGoodwinThenDop853 needs method fox_goodwin_then_dop853, got '", method_name(s), "'");
        return s;
    }

    NewmarkSettings s_;
    Newmark<System> first_;
    Dop853<System> then_;
    StateType interval_start_;
    bool handed_over_ = false;
    double handover_time_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace camfollower
