// SPDX-License-Identifier: BSD-3-Clause
// The nonlinear elements of a Mechanism (model/mechanism.hpp), every kind in one collection that the
// mechanism visits once per contract method. A closed set, in the spirit of Pinocchio's joint
// collection, but stored as one vector per kind: the visit is a loop per kind the compiler inlines (no
// virtual call, no variant switch per element in the time loop).
//
// An element kind E provides (Vector, Matrix: the mechanism's Eigen types; Sink: a tangent column sink
// with start_column() and add(dof, u, v)):
//
//   using Spec;                                    its description, as the builder holds it
//   struct State;                                  its per-run scratch and path memory (workspace)
//   static const std::vector<Spec>& specs(const MechanismBuilder&);   the builder's list of them
//   E(const Spec&, const NetworkSpec&, const SpeedProgram&);   resolve DOF names, validate (the camshaft's rotation)
//   const std::string& name() const;
//   int max_rank() const;                          tangent columns it can add
//   std::vector<int> tangent_dofs() const;         the DOFs those columns touch (sparse fill pattern)
//   void prepare(double t, State&) const;          time-only terms, once per step
//   void add_force(double t, q, v, State&, Vector& f) const;   f += its force; caches its response
//   void add_tangent(const State&, v, cq, cv, Sink&) const;    cq df/dq + cv df/dv as column pairs
//   void accepted(double t, State&) const;         after an accepted step (path memory)
//   void add_channel_names(std::vector<std::string>&) const;  then observe() writes as many values
//   double* observe(double t, const State&, q, v, double* out) const;
//   void add_event_names(std::vector<std::string>&) const;    then event_values() writes as many
//   double* event_values(const State&, double* g) const;      from the response add_force cached
//   int event_count() const;                       how many names add_event_names adds
//   void event_located(State&, int which, double time, int direction) const;   a stepper located
//                                                  its event `which` (0-based) at `time` (path memory
//                                                  that records switching instants takes them here)
//   -- statics (at rest: no rates) --
//   void add_static(double t, q, State&, Vector& r, Matrix& Kt) const;       r += F, Kt += dF/dq
//   void add_active_set_guess(const State&, q, Vector& r, Matrix& Kt) const; as if closed, where open
//   void add_quasi_static_rate(const State&, q, Vector& rate) const;          d r / dt at fixed q
//
// Adding a kind: its header (model/elements/), its spec list and add_ method in MechanismBuilder, and
// its name in MechanismElements (model/mechanism.hpp); the config reader and the bindings make it
// reachable. Its order in MechanismElements is the order of its channels and events.
#pragma once

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "camfollower/motion/speed_program.hpp"

namespace camfollower {

template <class... Kinds>
class ElementSet {
public:
    using States = std::tuple<std::vector<typename Kinds::State>...>;

    // Every kind's elements built from its specs in the builder, in the builder's order.
    template <class Builder, class Network>
    static ElementSet build(const Builder& builder, const Network& net, const SpeedProgram& drive) {
        ElementSet set;
        (set.fill<Kinds>(Kinds::specs(builder), net, drive), ...);
        return set;
    }

    template <class E>
    const std::vector<E>& of() const {
        return std::get<std::vector<E>>(elements_);
    }
    // One State per element (allocates: once per run).
    States states() const {
        States s;
        (std::get<std::vector<typename Kinds::State>>(s).resize(of<Kinds>().size()), ...);
        return s;
    }

    // e.event_located(...) for the element whose events include the mechanism's event `index`.
    template <class... A>
    void event_located(States& states, int index, A... args) const {
        int first = 0;
        for_each(states, [&](const auto& e, auto& s) {
            const int count = e.event_count();
            if (index >= first && index < first + count) e.event_located(s, index - first, args...);
            first += count;
        });
    }

    // f(element) for every element, kinds in the order listed.
    template <class F>
    void for_each(F&& f) const {
        (for_each_of<Kinds>(f), ...);
    }
    // f(element, its state) for every element.
    template <class F>
    void for_each(States& states, F&& f) const {
        (for_each_with<Kinds>(states, f), ...);
    }

private:
    template <class E, class Specs, class Network>
    void fill(const Specs& specs, const Network& net, const SpeedProgram& drive) {
        std::vector<E>& list = std::get<std::vector<E>>(elements_);
        list.reserve(specs.size());
        for (const auto& spec : specs) list.emplace_back(spec, net, drive);
    }
    template <class E, class F>
    void for_each_of(F& f) const {
        for (const E& e : of<E>()) f(e);
    }
    template <class E, class F>
    void for_each_with(States& states, F& f) const {
        const std::vector<E>& list = of<E>();
        std::vector<typename E::State>& s = std::get<std::vector<typename E::State>>(states);
        for (std::size_t i = 0; i < list.size(); ++i) f(list[i], s[i]);
    }

    std::tuple<std::vector<Kinds>...> elements_;
};

}  // namespace camfollower
