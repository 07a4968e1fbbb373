// SPDX-License-Identifier: BSD-3-Clause
// The second-order-system contract every integrator in camfollower works on:
//
//     M q'' + C q' + K q + f(t, q, q') = p(t)
//
// M, C, K constant; f the nonlinear (contact) forces, p the external loads. A system is any type with
//
//   required   using Vector, Matrix;                  Eigen column vector / square matrix types
//              int size() const;                      number of DOFs
//              const Matrix& mass() const;            M, symmetric positive definite
//              const Matrix& damping() const;         C
//              const Matrix& stiffness() const;       K
//   optional   void load(double t, Vector& p) const;  p(t) (absent: no load)
//              -- nonlinear terms, all or none --
//              using Workspace;                       time-only terms and path memory of one run
//              Workspace workspace() const;           a fresh workspace (may allocate)
//              void prepare(double t, Workspace&) const;   time-only terms at t (once per step)
//              void force(const Workspace&, const Vector& q, const Vector& v, Vector& f) const;
//                                                     f(t, q, v) - p(t) for the prepared t
//              int max_rank() const;                  bound on the tangent's rank (e.g. contacts)
//              void tangent(const Workspace&, const Vector& q, const Vector& v, double cq, double cv,
//                           LowRank<Vector>&) const;  cq df/dq + cv df/dv = U V^T, rank <= max_rank()
//              std::vector<std::string> dof_names() const;  DOF names for outputs (absent: "0", "1", ...)
//              Vector initial_displacement() const;      where a run starts (absent: zero)
//              Vector initial_velocity() const;          its velocity there (absent: zero, at rest)
//              -- optional with a Workspace --
//              void accepted(Workspace&, const Vector& q, const Vector& v) const;
//                                                     after each accepted step (path-dependent elements)
//              std::vector<std::string> channel_names() const;
//              void observe(const Workspace&, const Vector& q, const Vector& v, double* out) const;
//                                                     the named output channels at an accepted state
//              std::vector<std::string> event_names() const;
//              void event_values(const Workspace&, const Vector& q, const Vector& v, double* g) const;
//                                                     switching functions, called right after force() at
//                                                     the same q, v (may reuse what it cached): one per
//                                                     named event, > 0 in contact, <= 0 apart; where one
//                                                     changes sign the force stops being smooth (a
//                                                     contact's penetration, a clearance's wall gap), and
//                                                     the integrators locate that instant (solver/events.hpp)
//              void event_located(Workspace&, int index, double time, int direction) const;
//                                                     each crossing a stepper located (event `index` at
//                                                     `time`, direction +1 rose through zero, -1 fell),
//                                                     before accepted() at the end of its step: path
//                                                     memory that records switching instants (contact-
//                                                     loss intervals) takes them from here
//
// A system the sparse backend (solver/sparse_newmark.hpp) can run also has
//              const Eigen::SparseMatrix<double>& sparse_mass() const;   (and sparse_damping, sparse_stiffness)
//              std::vector<std::vector<int>> tangent_pattern() const;   the DOFs each tangent column can touch
//              void tangent(const Workspace&, const Vector& q, const Vector& v, double cq, double cv,
//                           SparseLowRank&) const;   the same tangent, each column on its few DOFs
//
// Call order within a step: prepare(t), then for each Newton iterate force(q, v) followed by
// tangent(q, v) at the same q, v; after acceptance force() at the accepted state, then accepted(). A
// system may therefore cache in the workspace what force() computed (mutable members) and reuse it in
// tangent() and accepted().
// A system without a Workspace is linear: f = -p(t). The tangent's rank is usually the number of
// active contacts, which keeps the Newton update a low-rank correction of a matrix factored once per
// time step size. Checked at compile time by check_system<S>() (static_assert with the missing member).
#pragma once

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "camfollower/detail/force_inline.hpp"

namespace camfollower {

// A rank-k matrix U V^T with n rows; the columns are allocated once (capacity) and `rank` says how
// many are in use, so filling it inside the time loop allocates nothing.
template <class Vector>
struct LowRank {
    using Columns = Eigen::Matrix<double, Vector::RowsAtCompileTime, Eigen::Dynamic>;
    Columns U, V;
    int rank = 0;

    LowRank() = default;
    LowRank(int rows, int capacity) : U(rows, capacity), V(rows, capacity) {}
    int capacity() const { return int(U.cols()); }
    void clear() { rank = 0; }
    // Append u v^T; the caller guarantees rank < capacity() (max_rank() of the system).
    template <class A, class B>
    void add(const A& u, const B& v) {
        U.col(rank) = u;
        V.col(rank) = v;
        ++rank;
    }
};

// A rank-k matrix U V^T whose column pairs each live on a few DOFs: column k has the entries
// [start[k], start[k + 1]) of (dof, u, v) (the last column runs to the end); entries of one column
// with the same DOF add up. Capacity is reserved once, so clear() and refilling allocate nothing.
struct SparseLowRank {
    std::vector<int> start, dof;
    std::vector<double> u, v;

    void reserve(std::size_t columns, std::size_t entries) {
        start.reserve(columns), dof.reserve(entries), u.reserve(entries), v.reserve(entries);
    }
    void clear() { start.clear(), dof.clear(), u.clear(), v.clear(); }
    int rank() const { return int(start.size()); }
    void start_column() { start.push_back(int(dof.size())); }
    void add(int d, double u_value, double v_value) { dof.push_back(d), u.push_back(u_value), v.push_back(v_value); }
    int begin(int k) const { return start[std::size_t(k)]; }
    int end(int k) const { return k + 1 < rank() ? start[std::size_t(k) + 1] : int(dof.size()); }
};

namespace detail {

template <class...>
using void_t = void;

#define CAMFOLLOWER_DETECT(name, expr) \
    template <class S, class = void>   \
    struct name : std::false_type {};  \
    template <class S>                 \
    struct name<S, void_t<decltype(expr)>> : std::true_type {};

template <class S>
using vector_t = typename S::Vector;

CAMFOLLOWER_DETECT(has_vector_type, std::declval<typename S::Vector>())
CAMFOLLOWER_DETECT(has_matrix_type, std::declval<typename S::Matrix>())
CAMFOLLOWER_DETECT(has_size, int(std::declval<const S&>().size()))
CAMFOLLOWER_DETECT(has_mass, static_cast<const typename S::Matrix&>(std::declval<const S&>().mass()))
CAMFOLLOWER_DETECT(has_damping, static_cast<const typename S::Matrix&>(std::declval<const S&>().damping()))
CAMFOLLOWER_DETECT(has_stiffness, static_cast<const typename S::Matrix&>(std::declval<const S&>().stiffness()))
CAMFOLLOWER_DETECT(has_load, std::declval<const S&>().load(0.0, std::declval<vector_t<S>&>()))
CAMFOLLOWER_DETECT(has_workspace_type, std::declval<typename S::Workspace>())
CAMFOLLOWER_DETECT(has_workspace, std::declval<typename S::Workspace&>() = std::declval<const S&>().workspace())
CAMFOLLOWER_DETECT(has_prepare, std::declval<const S&>().prepare(0.0, std::declval<typename S::Workspace&>()))
CAMFOLLOWER_DETECT(has_force,
                   std::declval<const S&>().force(std::declval<const typename S::Workspace&>(),
                                                  std::declval<const vector_t<S>&>(),
                                                  std::declval<const vector_t<S>&>(), std::declval<vector_t<S>&>()))
CAMFOLLOWER_DETECT(has_max_rank, int(std::declval<const S&>().max_rank()))
CAMFOLLOWER_DETECT(has_tangent, std::declval<const S&>().tangent(std::declval<const typename S::Workspace&>(),
                                                                 std::declval<const vector_t<S>&>(),
                                                                 std::declval<const vector_t<S>&>(), 0.0, 0.0,
                                                                 std::declval<LowRank<vector_t<S>>&>()))
CAMFOLLOWER_DETECT(has_accepted, std::declval<const S&>().accepted(std::declval<typename S::Workspace&>(),
                                                                   std::declval<const vector_t<S>&>(),
                                                                   std::declval<const vector_t<S>&>()))
CAMFOLLOWER_DETECT(has_event_located,
                   std::declval<const S&>().event_located(std::declval<typename S::Workspace&>(), 0, 0.0, 0))
CAMFOLLOWER_DETECT(has_channels, std::declval<std::vector<std::string>&>() = std::declval<const S&>().channel_names())
CAMFOLLOWER_DETECT(has_dof_names, std::declval<std::vector<std::string>&>() = std::declval<const S&>().dof_names())
CAMFOLLOWER_DETECT(has_initial_displacement,
                   std::declval<vector_t<S>&>() = std::declval<const S&>().initial_displacement())
CAMFOLLOWER_DETECT(has_initial_velocity, std::declval<vector_t<S>&>() = std::declval<const S&>().initial_velocity())
CAMFOLLOWER_DETECT(has_event_names, std::declval<std::vector<std::string>&>() = std::declval<const S&>().event_names())
CAMFOLLOWER_DETECT(has_event_values,
                   std::declval<const S&>().event_values(std::declval<const typename S::Workspace&>(),
                                                         std::declval<const vector_t<S>&>(),
                                                         std::declval<const vector_t<S>&>(), std::declval<double*>()))
CAMFOLLOWER_DETECT(has_observe,
                   std::declval<const S&>().observe(std::declval<const typename S::Workspace&>(),
                                                    std::declval<const vector_t<S>&>(),
                                                    std::declval<const vector_t<S>&>(), std::declval<double*>()))
#undef CAMFOLLOWER_DETECT

}  // namespace detail

// Systems driven by a camshaft have a period() (s): the time scale of their motion.
namespace detail {
template <class S, class = void>
struct has_period : std::false_type {};
template <class S>
struct has_period<S, void_t<decltype(double(std::declval<const S&>().period()))>> : std::true_type {};
}  // namespace detail

// A system whose forcing may not repeat every period (a camshaft speeding up) says so with
// periodic(); the periodic steady state refuses it.
namespace detail {
template <class S, class = void>
struct has_periodic : std::false_type {};
template <class S>
struct has_periodic<S, void_t<decltype(bool(std::declval<const S&>().periodic()))>> : std::true_type {};
}  // namespace detail

template <class S>
inline constexpr bool is_nonlinear_system_v = detail::has_workspace_type<S>::value;

// Compile-time check of the contract, with one message per missing member.
template <class S>
constexpr bool check_system() {
    static_assert(detail::has_vector_type<S>::value, "system: missing `using Vector = <Eigen column vector>`");
    static_assert(detail::has_matrix_type<S>::value, "system: missing `using Matrix = <Eigen matrix>`");
    static_assert(detail::has_size<S>::value, "system: missing `int size() const`");
    static_assert(detail::has_mass<S>::value, "system: missing `const Matrix& mass() const`");
    static_assert(detail::has_damping<S>::value, "system: missing `const Matrix& damping() const`");
    static_assert(detail::has_stiffness<S>::value, "system: missing `const Matrix& stiffness() const`");
    if constexpr (detail::has_workspace_type<S>::value) {
        static_assert(detail::has_workspace<S>::value,
                      "system with a Workspace: missing `Workspace workspace() const`");
        static_assert(detail::has_prepare<S>::value,
                      "system with a Workspace: missing `void prepare(double t, Workspace&) const`");
        static_assert(detail::has_force<S>::value,
                      "system with a Workspace: missing `void force(const Workspace&, const Vector& q, const "
                      "Vector& v, Vector& f) const`");
        static_assert(detail::has_max_rank<S>::value, "system with a Workspace: missing `int max_rank() const`");
        static_assert(detail::has_tangent<S>::value,
                      "system with a Workspace: missing `void tangent(const Workspace&, const Vector& q, const "
                      "Vector& v, double cq, double cv, LowRank<Vector>&) const`");
        static_assert(detail::has_channels<S>::value == detail::has_observe<S>::value,
                      "system: channel_names() and observe(...) go together");
        static_assert(detail::has_event_names<S>::value == detail::has_event_values<S>::value,
                      "system: event_names() and event_values(...) go together");
    } else {
        static_assert(!detail::has_event_names<S>::value,
                      "system: event_names() needs event_values(const Workspace&, ...), i.e. a Workspace");
        static_assert(!detail::has_channels<S>::value,
                      "system: channel_names() needs observe(const Workspace&, ...), i.e. a Workspace");
    }
    return true;
}

// Uniform access to the optional members: the integrators call these, never the members directly.
struct TimeOnlyWorkspace {
    double t = 0.0;
};

template <class S, bool = detail::has_workspace_type<S>::value>
struct workspace_of {
    using type = TimeOnlyWorkspace;  // a linear system: the workspace only remembers t for p(t)
};
template <class S>
struct workspace_of<S, true> {
    using type = typename S::Workspace;
};
template <class S>
using workspace_t = typename workspace_of<S>::type;

template <class S>
workspace_t<S> make_workspace(const S& s) {
    if constexpr (is_nonlinear_system_v<S>) return s.workspace();
    else return {};
}

template <class S>
void prepare(const S& s, double t, workspace_t<S>& ws) {
    if constexpr (is_nonlinear_system_v<S>) s.prepare(t, ws);
    else ws.t = t;
}

// f(t, q, v) - p(t) at the prepared time (forced inline: the hot path of every integrator).
template <class S, class V>
CAMFOLLOWER_FORCE_INLINE void nonlinear_force(const S& s, const workspace_t<S>& ws, const V& q, const V& v, V& f) {
    if constexpr (is_nonlinear_system_v<S>) {
        s.force(ws, q, v, f);
    } else if constexpr (detail::has_load<S>::value) {
        s.load(ws.t, f);
        f = -f;
    } else {
        (void)ws, (void)q, (void)v;
        f.setZero(s.size());
    }
}

template <class S>
int max_rank(const S& s) {
    if constexpr (is_nonlinear_system_v<S>) return s.max_rank();
    else return (void)s, 0;
}

template <class S, class V>
void tangent(const S& s, const workspace_t<S>& ws, const V& q, const V& v, double cq, double cv, LowRank<V>& uv) {
    uv.clear();
    if constexpr (is_nonlinear_system_v<S>) s.tangent(ws, q, v, cq, cv, uv);
    else (void)s, (void)ws, (void)q, (void)v, (void)cq, (void)cv;
}

template <class S, class V>
void accepted(const S& s, workspace_t<S>& ws, const V& q, const V& v) {
    if constexpr (detail::has_accepted<S>::value) s.accepted(ws, q, v);
    else (void)s, (void)ws, (void)q, (void)v;
}

template <class S>
void event_located(const S& s, workspace_t<S>& ws, int index, double time, int direction) {
    if constexpr (detail::has_event_located<S>::value) s.event_located(ws, index, time, direction);
    else (void)s, (void)ws, (void)index, (void)time, (void)direction;
}

template <class S>
std::vector<std::string> channel_names(const S& s) {
    if constexpr (detail::has_channels<S>::value) return s.channel_names();
    else return (void)s, std::vector<std::string>{};
}

template <class S>
std::vector<std::string> dof_names(const S& s) {
    if constexpr (detail::has_dof_names<S>::value) {
        return s.dof_names();
    } else {
        std::vector<std::string> names;
        for (int k = 0; k < s.size(); ++k) names.push_back(std::to_string(k));
        return names;
    }
}

template <class S>
typename S::Vector initial_displacement(const S& s) {
    if constexpr (detail::has_initial_displacement<S>::value) return s.initial_displacement();
    else return S::Vector::Zero(s.size());
}

template <class S>
typename S::Vector initial_velocity(const S& s) {
    if constexpr (detail::has_initial_velocity<S>::value) return s.initial_velocity();
    else return S::Vector::Zero(s.size());
}

template <class S, class V>
void observe(const S& s, const workspace_t<S>& ws, const V& q, const V& v, double* out) {
    if constexpr (detail::has_observe<S>::value) s.observe(ws, q, v, out);
    else (void)s, (void)ws, (void)q, (void)v, (void)out;
}

template <class S>
inline constexpr bool has_events_v = detail::has_event_names<S>::value&& detail::has_event_values<S>::value;

template <class S>
std::vector<std::string> event_names(const S& s) {
    if constexpr (has_events_v<S>) return s.event_names();
    else return (void)s, std::vector<std::string>{};
}

template <class S, class V>
void event_values(const S& s, const workspace_t<S>& ws, const V& q, const V& v, double* g) {
    if constexpr (has_events_v<S>) s.event_values(ws, q, v, g);
    else (void)s, (void)ws, (void)q, (void)v, (void)g;
}

}  // namespace camfollower
