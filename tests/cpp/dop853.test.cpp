// SPDX-License-Identifier: BSD-3-Clause
// The DOP853 tableau (solver/dop853_tableau.hpp) against the Runge-Kutta order conditions, computed
// here from the rooted trees (Butcher; Hairer, Norsett & Wanner, Solving ODE I, II.2): sum_i b_i
// Phi_i(t) = 1 / gamma(t) for every tree t of order <= 8, the dense output's weights b_i(theta) to
// order 7 (theta^|t| / gamma(t)), the embedded error estimates vanishing to orders 5 and 3. The
// method's observed orders, error control and events are tested with Dormand-Prince 5(4)'s
// (dormand_prince.test.cpp, events.test.cpp).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include "camfollower/solver/dop853_tableau.hpp"

namespace {

namespace tableau = camfollower::dop853;
constexpr std::size_t stages = std::size_t(tableau::all_stages);
using Weights = std::array<double, stages>;

// A rooted tree: its order, gamma (the density) and the elementary weights Phi_i of every stage,
// Phi(t) = prod over the root's subtrees s of (A Phi(s)), Phi(single node) = 1.
struct Tree {
    int order = 1;
    double gamma = 1.0;
    Weights phi{};
};

// Every rooted tree up to `max_order`: a tree of order n is a multiset of smaller trees (its root's
// subtrees) of orders summing to n - 1, enumerated as non-decreasing index lists (each tree once).
std::vector<Tree> trees_up_to(int max_order) {
    Tree node;
    node.phi.fill(1.0);
    std::vector<Tree> trees{node};
    std::vector<std::size_t> pick;
    for (int n = 2; n <= max_order; ++n) {
        const std::size_t known = trees.size();  // the trees of order < n
        std::function<void(std::size_t, int)> extend = [&](std::size_t first, int left) {
            if (left == 0) {
                Tree t;
                t.order = n;
                t.gamma = n;
                t.phi.fill(1.0);
                for (std::size_t s : pick) {
                    t.gamma *= trees[s].gamma;
                    for (std::size_t i = 0; i < stages; ++i) {
                        double ai = 0.0;
                        for (std::size_t j = 0; j < i; ++j) ai += tableau::a[i][j] * trees[s].phi[j];
                        t.phi[i] *= ai;
                    }
                }
                trees.push_back(t);
                return;
            }
            for (std::size_t s = first; s < known; ++s) {
                if (trees[s].order > left) continue;
                pick.push_back(s);
                extend(s, left - trees[s].order);
                pick.pop_back();
            }
        };
        extend(0, n - 1);
    }
    return trees;
}

double dot(const Weights& w, const Weights& phi) {
    double sum = 0.0;
    for (std::size_t i = 0; i < stages; ++i) sum += w[i] * phi[i];
    return sum;
}

// The weights b (row 12 of a: the solution), padded to all stages.
Weights solution_weights() {
    Weights b{};
    for (std::size_t i = 0; i < 12; ++i) b[i] = tableau::a[12][i];
    return b;
}

// The dense output's weights: y(t0 + theta h) = y0 + h sum_i b_i(theta) k_i, from the interpolant
// y0 + theta (r1 + (1 - theta) (r2 + theta (r3 + (1 - theta) (r4 + ...)))) with r1 = y1 - y0 = h b.k,
// r2 = h k_0 - r1, r3 = r1 - h k_12 - r2 (k_12 = f at y1) and r4..r7 = h d.k.
Weights dense_weights(double theta) {
    const Weights b = solution_weights();
    std::array<Weights, 7> r{};
    for (std::size_t i = 0; i < stages; ++i) {
        r[0][i] = b[i];
        r[1][i] = (i == 0 ? 1.0 : 0.0) - b[i];
        r[2][i] = 2.0 * b[i] - (i == 0 ? 1.0 : 0.0) - (i == 12 ? 1.0 : 0.0);
        for (std::size_t k = 0; k < 4; ++k) r[3 + k][i] = tableau::d[k][i];
    }
    Weights w{};
    for (std::size_t i = 0; i < stages; ++i) {
        double acc = r[6][i];
        for (std::size_t j = 6; j-- > 0;) acc = r[j][i] + (j % 2 == 0 ? 1.0 - theta : theta) * acc;
        w[i] = theta * acc;
    }
    return w;
}

}  // namespace

TEST_CASE("DOP853 tableau: rows of a sum to c, every stage") {
    for (std::size_t i = 0; i < stages; ++i) {
        double sum = 0.0;
        for (std::size_t j = 0; j < i; ++j) sum += tableau::a[i][j];
        CAPTURE(i, sum, tableau::c[i]);
        CHECK(std::abs(sum - tableau::c[i]) < 1e-14);
    }
}

TEST_CASE("DOP853 tableau: the quadrature conditions sum b_i c_i^(k-1) = 1/k, k = 1..8") {
    const Weights b = solution_weights();
    for (int k = 1; k <= 8; ++k) {
        double sum = 0.0;
        for (std::size_t i = 0; i < stages; ++i) sum += b[i] * std::pow(tableau::c[i], k - 1);
        CAPTURE(k, sum);
        CHECK(std::abs(sum - 1.0 / k) < 1e-14);
    }
}

TEST_CASE("DOP853 tableau: all 200 order conditions of order <= 8 (rooted trees)") {
    const std::vector<Tree> trees = trees_up_to(8);
    std::array<int, 9> count{};
    for (const Tree& t : trees) ++count[std::size_t(t.order)];
    // The number of rooted trees of order 1..8 (OEIS A000081).
    CHECK(count == std::array<int, 9>{0, 1, 1, 2, 4, 9, 20, 48, 115});
    const Weights b = solution_weights();
    double worst = 0.0;
    for (const Tree& t : trees) worst = std::max(worst, std::abs(dot(b, t.phi) * t.gamma - 1.0));
    CAPTURE(worst);
    CHECK(worst < 1e-12);  // relative to 1 / gamma
    // And the method is not of order 9: some tree of order 9 fails.
    double worst9 = 0.0;
    for (const Tree& t : trees_up_to(9))
        if (t.order == 9) worst9 = std::max(worst9, std::abs(dot(b, t.phi) * t.gamma - 1.0));
    CAPTURE(worst9);
    CHECK(worst9 > 1e-6);
}

TEST_CASE("DOP853 tableau: the error estimates vanish on the trees of order <= 5 (e5) and <= 3 (e3)") {
    const std::vector<Tree> trees = trees_up_to(6);
    for (auto [e, order] : {std::pair{&tableau::e5, 5}, std::pair{&tableau::e3, 3}}) {
        Weights w{};
        for (std::size_t i = 0; i < e->size(); ++i) w[i] = (*e)[i];
        double within = 0.0, beyond = 0.0;
        for (const Tree& t : trees) {
            const double residual = std::abs(dot(w, t.phi) * t.gamma);
            (t.order <= order ? within : beyond) = std::max(t.order <= order ? within : beyond, residual);
        }
        CAPTURE(order, within, beyond);
        CHECK(within < 1e-12);
        CHECK(beyond > 1e-6);  // an estimate of the error of order `order` + 1
    }
}

TEST_CASE("DOP853 tableau: the dense output is of order 7 at every theta, and ends at the solution") {
    const std::vector<Tree> trees = trees_up_to(8);
    for (double theta : {0.1, 0.25, 0.5, 0.7, 0.9, 1.0}) {
        const Weights w = dense_weights(theta);
        double worst = 0.0, worst8 = 0.0;
        for (const Tree& t : trees) {
            const double residual = std::abs(dot(w, t.phi) * t.gamma - std::pow(theta, t.order));
            (t.order <= 7 ? worst : worst8) = std::max(t.order <= 7 ? worst : worst8, residual);
        }
        CAPTURE(theta, worst, worst8);
        CHECK(worst < 1e-12);
        if (theta < 1.0) CHECK(worst8 > 1e-7);  // order 7 inside the step, not 8
    }
    const Weights end = dense_weights(1.0), b = solution_weights();
    for (std::size_t i = 0; i < stages; ++i) CHECK(std::abs(end[i] - b[i]) < 1e-14);
}
