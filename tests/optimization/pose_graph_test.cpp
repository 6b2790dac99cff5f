// Unit tests of the pose graph back end (golden/optimization, docs/algorithms.md "Pose graph
// back end"), through its public API only, against ground-truth trajectories built here.
//
// The oracles, and the bounds (each test prints its measured values as "[optimization] ..."):
// - a consistent graph (odometry from the truth) stays put within 1e-9, from the truth and
//   from the composed odometry.
// - a 40-node square loop with noisy odometry and exact loop closures: within 5 mm and 2 mrad
//   of the truth, ten times better than the odometry chain; the same from a guess 2 m and
//   1.5 rad off.
// - three nodes with a known answer: two conflicting measurements of equal sigma average.
// - one grossly wrong loop closure: robust, it moves the solution less than a fifth of what
//   it does non-robust, and it is the one downweighted edge.
// - bad indices, sigmas, measurements and options throw.
// - a circle whose headings cross +-pi: zero cost when consistent, converges when noisy.
// - fixed nodes stay; an unreached node stays; with no node fixed the relative poses still
//   converge; the same graph gives the same poses bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "intgrid/core/types.hpp"
#include "intgrid/optimization/pose_graph.hpp"

using intgrid::core::compose;
using intgrid::core::Pose2;
using intgrid::core::relative;
using intgrid::core::wrap_angle;
using namespace intgrid::optimization;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kOdoXy = 0.05;  // odometry standard deviations (m, rad)
constexpr double kOdoTh = 0.02;
constexpr double kLoopXy = 1e-3;  // exact loop closures, tight
constexpr double kLoopTh = 1e-3;

// The truth of a square loop: `side` steps of 1 m a side, turning 90 degrees at each corner,
// 4 * side nodes (the step from the last node closes the loop on node 0).
std::vector<Pose2> square_truth(int side) {
  std::vector<Pose2> truth{{0.0, 0.0, 0.0}};
  for (int i = 0; i + 1 < 4 * side; ++i) {
    const Pose2 u{1.0, 0.0, i % side == side - 1 ? kPi / 2.0 : 0.0};
    truth.push_back(compose(truth.back(), u));
  }
  return truth;
}

// Odometry increments between consecutive true poses, with seeded normal noise.
std::vector<Pose2> noisy_odometry(const std::vector<Pose2>& truth, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> nxy(0.0, kOdoXy), nth(0.0, kOdoTh);
  std::vector<Pose2> odometry;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    Pose2 u = relative(truth[i], truth[i + 1]);
    u.x += nxy(rng);
    u.y += nxy(rng);
    u.theta += nth(rng);
    odometry.push_back(u);
  }
  return odometry;
}

// Dead reckoning: the odometry chain composed from the first true pose.
std::vector<Pose2> chain(const Pose2& start, const std::vector<Pose2>& odometry) {
  std::vector<Pose2> poses{start};
  for (const Pose2& u : odometry) poses.push_back(compose(poses.back(), u));
  return poses;
}

Edge exact_edge(const std::vector<Pose2>& truth, std::size_t from, std::size_t to, double sxy,
                double sth, bool robust = false) {
  return {from, to, relative(truth[from], truth[to]), sxy, sth, robust};
}

PoseGraph odometry_graph(const std::vector<Pose2>& initial, const std::vector<Pose2>& odometry) {
  PoseGraph graph;
  for (const Pose2& p : initial) graph.add_node(p);
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    graph.add_edge({i, i + 1, odometry[i], kOdoXy, kOdoTh});
  }
  return graph;
}

// Exact closures from each node to the nodes three and four back, and the loop's end to its
// start: they alone pin every pose, the noisy odometry only pulls against them.
void add_exact_closures(PoseGraph& graph, const std::vector<Pose2>& truth) {
  const std::size_t n = truth.size();
  for (std::size_t i = 3; i < n; ++i) {
    graph.add_edge(exact_edge(truth, i - 3, i, kLoopXy, kLoopTh));
    if (i >= 4) graph.add_edge(exact_edge(truth, i - 4, i, kLoopXy, kLoopTh));
  }
  graph.add_edge(exact_edge(truth, n - 1, 0, kLoopXy, kLoopTh));
  graph.add_edge(exact_edge(truth, n - 2, 0, kLoopXy, kLoopTh));
}

struct Error {
  double xy = 0.0;     // largest position error (m)
  double theta = 0.0;  // largest heading error (rad), wrapped
};

Error max_error(const std::vector<Pose2>& a, const std::vector<Pose2>& b) {
  Error e;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e.xy = std::max(e.xy, std::hypot(a[i].x - b[i].x, a[i].y - b[i].y));
    e.theta = std::max(e.theta, std::abs(wrap_angle(a[i].theta - b[i].theta)));
  }
  return e;
}

// (a) A consistent graph stays put.
TEST(PoseGraph, ConsistentGraphStaysPut) {
  std::vector<Pose2> truth{{0.5, -1.0, 0.3}};
  for (int i = 0; i < 30; ++i) {
    truth.push_back(compose(truth.back(), {0.4 + 0.01 * i, 0.05, 0.1 * std::sin(0.3 * i)}));
  }
  std::vector<Pose2> odometry;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    odometry.push_back(relative(truth[i], truth[i + 1]));
  }
  for (const auto& initial : {truth, chain(truth[0], odometry)}) {
    PoseGraph graph = odometry_graph(initial, odometry);
    const OptimizeSummary summary = graph.optimize();
    const Error e = max_error(graph.poses(), truth);
    std::printf(
        "[optimization] consistent: %d iterations, cost %.3g -> %.3g, error %.3g m %.3g rad\n",
        summary.iterations, summary.initial_cost, summary.final_cost, e.xy, e.theta);
    EXPECT_LT(e.xy, 1e-9);
    EXPECT_LT(e.theta, 1e-9);
    EXPECT_LE(summary.final_cost, summary.initial_cost);
    EXPECT_LT(summary.final_cost, 1e-12);
    EXPECT_EQ(summary.downweighted_edges, 0u);
    EXPECT_EQ(graph.poses()[0], truth[0]);  // node 0 is fixed
  }
}

// (b) A square loop with noisy odometry and exact loop closures converges to the truth.
TEST(PoseGraph, SquareLoopConvergesToTruth) {
  const std::vector<Pose2> truth = square_truth(10);
  ASSERT_EQ(truth.size(), 40u);
  const std::vector<Pose2> odometry = noisy_odometry(truth, 7);
  const std::vector<Pose2> dead_reckoning = chain(truth[0], odometry);
  PoseGraph graph = odometry_graph(dead_reckoning, odometry);
  add_exact_closures(graph, truth);
  const OptimizeSummary summary = graph.optimize();
  const Error before = max_error(dead_reckoning, truth);
  const Error after = max_error(graph.poses(), truth);
  std::printf(
      "[optimization] square: %zu edges, %d iterations, cost %.4g -> %.4g; odometry "
      "%.3f m %.4f rad, optimized %.5f m %.6f rad\n",
      graph.edges(), summary.iterations, summary.initial_cost, summary.final_cost, before.xy,
      before.theta, after.xy, after.theta);
  EXPECT_GT(before.xy, 0.1);  // the odometry chain has drifted
  EXPECT_LT(after.xy, 5e-3);
  EXPECT_LT(after.theta, 2e-3);
  EXPECT_LT(after.xy * 10.0, before.xy);
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  EXPECT_LE(summary.iterations, OptimizeOptions{}.max_iterations);
}

// The damping brings a bad initial guess (every free node up to 2 m and 1.5 rad off the truth,
// uniformly) to the same solution as the odometry chain's.
TEST(PoseGraph, BadInitialGuessConverges) {
  const std::vector<Pose2> truth = square_truth(10);
  const std::vector<Pose2> odometry = noisy_odometry(truth, 7);
  PoseGraph reference = odometry_graph(chain(truth[0], odometry), odometry);
  add_exact_closures(reference, truth);
  reference.optimize();

  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Pose2> initial = truth;
  for (std::size_t i = 1; i < initial.size(); ++i) {
    initial[i].x += 2.0 * u(rng);
    initial[i].y += 2.0 * u(rng);
    initial[i].theta += 1.5 * u(rng);
  }
  PoseGraph graph = odometry_graph(initial, odometry);
  add_exact_closures(graph, truth);
  const OptimizeSummary summary = graph.optimize();
  const Error start = max_error(initial, truth);
  const Error e = max_error(graph.poses(), truth);
  const Error to_reference = max_error(graph.poses(), reference.poses());
  std::printf(
      "[optimization] bad initial guess (%.2f m %.2f rad off): %d iterations, cost %.4g "
      "-> %.4g, error %.5f m %.6f rad, %.3g m from the odometry start's solution\n",
      start.xy, start.theta, summary.iterations, summary.initial_cost, summary.final_cost, e.xy,
      e.theta, to_reference.xy);
  EXPECT_GT(start.theta, 1.0);
  EXPECT_LT(summary.iterations, OptimizeOptions{}.max_iterations);
  EXPECT_LT(e.xy, 5e-3);
  EXPECT_LT(e.theta, 2e-3);
  EXPECT_LT(to_reference.xy, 1e-6);
}

// Three nodes: node 1 pinned by one edge from node 0, node 2 measured twice from node 1 with
// equal sigmas, first at (1, 0, 0.1), then at `second`.
PoseGraph three_nodes(const Pose2& second) {
  PoseGraph graph;
  graph.add_node({0.0, 0.0, 0.0});
  graph.add_node({0.8, 0.3, 1.2});
  graph.add_node({1.0, 2.5, 2.0});
  graph.add_edge({0, 1, {1.0, 0.0, kPi / 2.0}, 0.1, 0.05});
  graph.add_edge({1, 2, {1.0, 0.0, 0.1}, 0.2, 0.1});
  graph.add_edge({1, 2, second, 0.2, 0.1});
  return graph;
}

// (c) Three nodes with a known answer: node 2 lands at its two measurements' midpoint in node
// 1's frame.
TEST(PoseGraph, ConflictingMeasurementsAverage) {
  PoseGraph graph = three_nodes({1.2, 0.2, 0.3});
  const OptimizeSummary summary = graph.optimize();
  const Pose2 node1{1.0, 0.0, kPi / 2.0};
  const Pose2 node2 = compose(node1, {1.1, 0.1, 0.2});
  const std::vector<Pose2>& p = graph.poses();
  std::printf("[optimization] three nodes: %d iterations, node 2 (%.12f, %.12f, %.12f)\n",
              summary.iterations, p[2].x, p[2].y, p[2].theta);
  EXPECT_NEAR(p[1].x, node1.x, 1e-9);
  EXPECT_NEAR(p[1].y, node1.y, 1e-9);
  EXPECT_NEAR(p[1].theta, node1.theta, 1e-9);
  EXPECT_NEAR(p[2].x, node2.x, 1e-9);
  EXPECT_NEAR(p[2].y, node2.y, 1e-9);
  EXPECT_NEAR(p[2].theta, node2.theta, 1e-9);
  // Each measurement is off by (0.1, 0.1, 0.1) from the midpoint: 0.5 * 2 * (2 * 0.25 + 1).
  EXPECT_NEAR(summary.final_cost, 1.5, 1e-9);
}

// A measurement taken again replaces the first: the same three nodes as above, node 2's second
// measurement replaced by the first's value, so both agree and node 2 lands on it with no cost
// left; a graph built with the value from the start gives the same poses.
TEST(PoseGraph, AMeasurementTakenAgainReplacesTheFirst) {
  PoseGraph again = three_nodes({1.2, 0.2, 0.3});
  again.set_measurement(2, {1.0, 0.0, 0.1});
  EXPECT_EQ(again.edge_list()[2].measured.x, 1.0);
  const OptimizeSummary summary = again.optimize();
  PoseGraph agreeing = three_nodes({1.0, 0.0, 0.1});
  agreeing.optimize();
  const Pose2 node2 = compose({1.0, 0.0, kPi / 2.0}, {1.0, 0.0, 0.1});
  EXPECT_NEAR(again.poses()[2].x, node2.x, 1e-9);
  EXPECT_NEAR(again.poses()[2].y, node2.y, 1e-9);
  EXPECT_NEAR(again.poses()[2].theta, node2.theta, 1e-9);
  EXPECT_NEAR(summary.final_cost, 0.0, 1e-12);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(again.poses()[i].x, agreeing.poses()[i].x) << i;
    EXPECT_EQ(again.poses()[i].y, agreeing.poses()[i].y) << i;
    EXPECT_EQ(again.poses()[i].theta, agreeing.poses()[i].theta) << i;
  }
  EXPECT_THROW(again.set_measurement(3, {}), std::out_of_range);
  EXPECT_THROW(again.set_measurement(0, {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}),
               std::invalid_argument);
  EXPECT_EQ(again.edge_list()[0].measured.x, 1.0);  // a refused measurement changes nothing
}

// A measurement taken again with less information along one direction: node 2 lands at the two
// measurements' mean in node 1's frame, weighted along that direction (x) by the information,
// evenly across it and in heading.
TEST(PoseGraph, InformationMeasuredAgainWeighsTheMeasurement) {
  PoseGraph graph = three_nodes({1.0, 0.0, 0.1});
  constexpr double kWeight = 0.25;
  graph.set_measurement(2, {1.2, 0.2, 0.3}, 0.0, kWeight);
  EXPECT_EQ(graph.edge_list()[2].weak_weight, kWeight);
  graph.optimize();
  const Pose2 in_node1 = relative(graph.poses()[1], graph.poses()[2]);
  EXPECT_NEAR(in_node1.x, (1.0 + kWeight * 1.2) / (1.0 + kWeight), 1e-9);
  EXPECT_NEAR(in_node1.y, 0.1, 1e-9);
  EXPECT_NEAR(in_node1.theta, 0.2, 1e-9);
  EXPECT_THROW(graph.set_measurement(3, {}, 0.0, 1.0), std::out_of_range);
  EXPECT_THROW(graph.set_measurement(2, {}, 0.0, 1.5), std::invalid_argument);
  EXPECT_THROW(graph.set_measurement(2, {}, std::numeric_limits<double>::infinity(), 1.0),
               std::invalid_argument);
  EXPECT_THROW(
      graph.set_measurement(2, {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}, 0.0, 1.0),
      std::invalid_argument);
  EXPECT_EQ(graph.edge_list()[2].measured.x, 1.2);  // a refused measurement changes nothing
  EXPECT_EQ(graph.edge_list()[2].weak_weight, kWeight);
}

// (d) One grossly wrong loop closure among many correct ones: with the Huber loss it moves the
// solution far less than without, and it is the one edge past huber_scale.
TEST(PoseGraph, RobustEdgeResistsAnOutlier) {
  const std::vector<Pose2> truth = square_truth(10);
  const std::size_t n = truth.size();
  const auto build = [&](bool outlier, bool robust) {
    PoseGraph graph;
    for (const Pose2& p : truth) graph.add_node(p);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      graph.add_edge(exact_edge(truth, i, i + 1, kOdoXy, kOdoTh));
    }
    for (std::size_t i = 0; i < n; ++i) {  // correct closures across the square
      graph.add_edge(exact_edge(truth, i, (i + n / 2 + i % 3) % n, kOdoXy, kOdoTh, true));
    }
    if (outlier) {
      Edge bad = exact_edge(truth, 10, 30, kOdoXy, kOdoTh, robust);
      bad.measured.x += 3.0;
      bad.measured.y -= 2.0;
      bad.measured.theta += 0.8;
      graph.add_edge(bad);
    }
    return graph;
  };
  PoseGraph clean = build(false, true);
  const OptimizeSummary clean_summary = clean.optimize();
  EXPECT_EQ(clean_summary.downweighted_edges, 0u);
  EXPECT_LT(max_error(clean.poses(), truth).xy, 1e-9);

  PoseGraph robust = build(true, true);
  PoseGraph plain = build(true, false);
  const OptimizeSummary robust_summary = robust.optimize();
  const OptimizeSummary plain_summary = plain.optimize();
  const Error robust_shift = max_error(robust.poses(), truth);
  const Error plain_shift = max_error(plain.poses(), truth);
  std::printf(
      "[optimization] outlier: robust %d iterations, moved %.4f m %.4f rad, %zu "
      "downweighted; plain %d iterations, moved %.4f m %.4f rad\n",
      robust_summary.iterations, robust_shift.xy, robust_shift.theta,
      robust_summary.downweighted_edges, plain_summary.iterations, plain_shift.xy,
      plain_shift.theta);
  EXPECT_GT(plain_shift.xy, 0.2);
  EXPECT_LT(robust_shift.xy * 5.0, plain_shift.xy);
  EXPECT_LT(robust_shift.theta * 5.0, plain_shift.theta);
  EXPECT_EQ(robust_summary.downweighted_edges, 1u);
}

// (d2) The same outlier switched off: its whitened error at the true poses is what the
// measurement's offset gives in its sigmas, and with it inactive the graph solves to the truth,
// as if the edge were not there; switched on again, it pulls as before.
TEST(PoseGraph, AnInactiveEdgeAddsNothing) {
  const std::vector<Pose2> truth = square_truth(10);
  const std::size_t n = truth.size();
  PoseGraph graph;
  for (const Pose2& p : truth) graph.add_node(p);
  for (std::size_t i = 0; i + 1 < n; ++i)
    graph.add_edge(exact_edge(truth, i, i + 1, kOdoXy, kOdoTh));
  Edge bad = exact_edge(truth, 10, 30, kOdoXy, kOdoTh, true);
  bad.measured.x += 3.0;
  bad.measured.y -= 2.0;
  bad.measured.theta += 0.8;
  graph.add_edge(bad);
  const std::size_t bad_index = graph.edges() - 1;
  EXPECT_NEAR(graph.whitened_error(bad_index),
              std::sqrt((9.0 + 4.0) / (kOdoXy * kOdoXy) + 0.64 / (kOdoTh * kOdoTh)), 1e-9);
  EXPECT_NEAR(graph.whitened_error(0), 0.0, 1e-12);

  graph.set_active(bad_index, false);
  EXPECT_FALSE(graph.edge_list()[bad_index].active);
  const OptimizeSummary off = graph.optimize();
  EXPECT_EQ(off.initial_cost, 0.0);
  EXPECT_LT(max_error(graph.poses(), truth).xy, 1e-12);
  EXPECT_EQ(off.downweighted_edges, 0u);

  graph.set_active(bad_index, true);
  const OptimizeSummary on = graph.optimize();
  EXPECT_GT(on.initial_cost, 0.0);
  EXPECT_GT(max_error(graph.poses(), truth).xy, 0.1);
  EXPECT_THROW(graph.set_active(graph.edges(), false), std::out_of_range);
  EXPECT_THROW((void)graph.whitened_error(graph.edges()), std::out_of_range);
}

// A measurement weak along an axis: two measurements of node 1 in node 0's frame (fixed at a
// turned pose), one isotropic and loose, one tight but with weak_weight of its information
// along weak_axis. With the headings agreeing, the answer in node 0's frame is the
// information-weighted mean (A_1 + A_2)^-1 (A_1 m_1 + A_2 m_2), solved here in closed form.
TEST(PoseGraph, AWeakEdgeGivesItsInformationAlongItsAxisOnly) {
  const Pose2 origin{1.0, 2.0, 0.7};
  const Pose2 loose{1.0, 0.5, 0.1}, tight{2.0, -0.5, 0.1};
  const double axis = 0.4;
  for (const double weak_weight : {0.0, 0.3, 1.0}) {
    PoseGraph graph;
    graph.add_node(origin);
    graph.add_node(compose(origin, {1.5, 0.0, 0.0}));
    graph.add_edge({0, 1, loose, 1.0, 0.1});
    Edge weak{0, 1, tight, 0.1, 0.1};
    weak.weak_axis = axis;
    weak.weak_weight = weak_weight;
    graph.add_edge(weak);
    const double c = std::cos(axis), s = std::sin(axis);
    // A_2 = (I - (1 - w) d d^T) / 0.01, A_1 = I.
    const double axx = (1.0 - (1.0 - weak_weight) * c * c) / 0.01,
                 axy = -(1.0 - weak_weight) * c * s / 0.01,
                 ayy = (1.0 - (1.0 - weak_weight) * s * s) / 0.01;
    const double hxx = 1.0 + axx, hxy = axy, hyy = 1.0 + ayy;
    const double bx = loose.x + axx * tight.x + axy * tight.y,
                 by = loose.y + axy * tight.x + ayy * tight.y;
    const double det = hxx * hyy - hxy * hxy;
    const Pose2 expected =
        compose(origin, {(hyy * bx - hxy * by) / det, (hxx * by - hxy * bx) / det, loose.theta});
    graph.optimize();
    const Pose2& got = graph.poses()[1];
    std::printf("[optimization] weak weight %.1f: (%.6f, %.6f) against (%.6f, %.6f)\n", weak_weight,
                got.x, got.y, expected.x, expected.y);
    EXPECT_NEAR(got.x, expected.x, 1e-9) << weak_weight;
    EXPECT_NEAR(got.y, expected.y, 1e-9) << weak_weight;
    EXPECT_NEAR(wrap_angle(got.theta - expected.theta), 0.0, 1e-9) << weak_weight;
    // The tight measurement's whitened error: its residual's parts across and along the axis.
    const Pose2 local = relative(origin, got);
    const double rx = local.x - tight.x, ry = local.y - tight.y;
    const double along = rx * c + ry * s, across = -rx * s + ry * c;
    EXPECT_NEAR(graph.whitened_error(1),
                std::sqrt((across * across + weak_weight * along * along) / 0.01), 1e-9);
  }
}

// (e) Bad indices, sigmas, measurements and options throw.
TEST(PoseGraph, RejectsBadInput) {
  PoseGraph graph;
  graph.add_node({});
  graph.add_node({1.0, 0.0, 0.0});
  const Pose2 m{1.0, 0.0, 0.0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(graph.add_edge({0, 2, m, 0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({5, 1, m, 0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({1, 1, m, 0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, m, 0.0, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, m, -0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, m, 0.1, 0.0}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, m, 0.1, -1.0}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, m, nan, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, m, 0.1, inf}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge({0, 1, {nan, 0.0, 0.0}, 0.1, 0.1}), std::invalid_argument);
  EXPECT_THROW(graph.add_edge(Edge{}), std::invalid_argument);  // sigmas default to 0
  for (const double weak_weight : {-0.1, 1.5, nan}) {
    Edge e{0, 1, m, 0.1, 0.1};
    e.weak_weight = weak_weight;
    EXPECT_THROW(graph.add_edge(e), std::invalid_argument) << weak_weight;
  }
  Edge no_axis{0, 1, m, 0.1, 0.1};
  no_axis.weak_axis = inf;
  EXPECT_THROW(graph.add_edge(no_axis), std::invalid_argument);
  EXPECT_EQ(graph.edges(), 0u);
  EXPECT_NO_THROW(graph.add_edge({0, 1, m, 0.1, 0.1}));
  EXPECT_EQ(graph.edges(), 1u);

  EXPECT_THROW(graph.set_fixed(2), std::out_of_range);
  EXPECT_THROW(graph.set_pose(2, {}), std::out_of_range);
  EXPECT_THROW(graph.set_pose(1, {0.0, inf, 0.0}), std::invalid_argument);
  EXPECT_THROW(graph.add_node({nan, 0.0, 0.0}), std::invalid_argument);
  EXPECT_EQ(graph.nodes(), 2u);
  EXPECT_THROW(graph.optimize({.max_iterations = -1}), std::invalid_argument);
  EXPECT_THROW(graph.optimize({.huber_scale = 0.0}), std::invalid_argument);
  EXPECT_THROW(graph.optimize({.tolerance = -1.0}), std::invalid_argument);
  EXPECT_THROW(graph.optimize({.tolerance = nan}), std::invalid_argument);
}

// (f) Angle wrap: a circle whose headings cross +-pi, stored unwrapped or wrapped.
TEST(PoseGraph, HeadingsCrossingPi) {
  const int n = 24;
  const double radius = 5.0, step = 2.0 * kPi / n;
  // Counter-clockwise on the circle, heading along the tangent, starting at heading 3.0.
  std::vector<Pose2> truth;
  for (int i = 0; i < n; ++i) {
    const double heading = 3.0 + step * i;  // from 3.0 to beyond 3.0 + 2 pi - step
    const double bearing = heading - kPi / 2.0;
    truth.push_back({radius * std::cos(bearing), radius * std::sin(bearing), heading});
  }
  std::vector<Pose2> wrapped = truth;
  for (Pose2& p : wrapped) p.theta = wrap_angle(p.theta);
  ASSERT_GT(wrapped[0].theta, 0.0);
  ASSERT_LT(wrapped[1].theta, 0.0);  // 3.0 + 0.26 is past pi

  // Consistent, with headings unwrapped or wrapped: no cost at all.
  for (const auto& initial : {truth, wrapped}) {
    PoseGraph graph;
    for (const Pose2& p : initial) graph.add_node(p);
    for (int i = 0; i < n; ++i) graph.add_edge(exact_edge(truth, i, (i + 1) % n, kOdoXy, kOdoTh));
    const OptimizeSummary summary = graph.optimize();
    EXPECT_LT(summary.initial_cost, 1e-20);
    EXPECT_LT(max_error(graph.poses(), truth).xy, 1e-9);
    EXPECT_LT(max_error(graph.poses(), truth).theta, 1e-9);
  }

  // Noisy odometry and exact closures: converges, headings come out wrapped.
  const std::vector<Pose2> odometry = noisy_odometry(truth, 11);
  const std::vector<Pose2> dead_reckoning = chain(truth[0], odometry);
  PoseGraph graph = odometry_graph(dead_reckoning, odometry);
  add_exact_closures(graph, truth);
  const OptimizeSummary summary = graph.optimize();
  const Error before = max_error(dead_reckoning, truth);
  const Error after = max_error(graph.poses(), truth);
  std::printf(
      "[optimization] circle across pi: %d iterations, cost %.4g -> %.4g; odometry "
      "%.3f m, optimized %.5f m %.6f rad\n",
      summary.iterations, summary.initial_cost, summary.final_cost, before.xy, after.xy,
      after.theta);
  EXPECT_LT(after.xy, 5e-3);
  EXPECT_LT(after.theta, 2e-3);
  EXPECT_LT(after.xy * 10.0, before.xy);
  for (std::size_t i = 1; i < graph.poses().size(); ++i) {
    EXPECT_GT(graph.poses()[i].theta, -kPi);
    EXPECT_LE(graph.poses()[i].theta, kPi);
  }
}

// Fixed nodes keep their poses; an extra fixed node pins the graph where it is told.
TEST(PoseGraph, FixedNodesStay) {
  const std::vector<Pose2> truth = square_truth(5);
  const std::vector<Pose2> odometry = noisy_odometry(truth, 3);
  PoseGraph graph = odometry_graph(chain(truth[0], odometry), odometry);
  add_exact_closures(graph, truth);
  EXPECT_TRUE(graph.is_fixed(0));
  EXPECT_FALSE(graph.is_fixed(7));
  const Pose2 pinned{4.0, 1.0, 2.0};  // deliberately inconsistent
  graph.set_pose(7, pinned);
  graph.set_fixed(7);
  graph.optimize();
  EXPECT_EQ(graph.poses()[0], truth[0]);
  EXPECT_EQ(graph.poses()[7], pinned);

  // A graph with every node fixed is left alone.
  PoseGraph all_fixed = odometry_graph(truth, odometry);
  for (std::size_t i = 0; i < truth.size(); ++i) all_fixed.set_fixed(i);
  const OptimizeSummary summary = all_fixed.optimize();
  EXPECT_EQ(summary.iterations, 0);
  EXPECT_EQ(all_fixed.poses(), truth);
  EXPECT_EQ(summary.initial_cost, summary.final_cost);
}

// A free node no edge reaches stays where it is; with no node fixed the damping still keeps
// the system solvable, and the relative poses converge (only the gauge is free).
TEST(PoseGraph, UnconstrainedNodes) {
  const std::vector<Pose2> truth = square_truth(5);
  const std::vector<Pose2> odometry = noisy_odometry(truth, 9);
  PoseGraph graph = odometry_graph(chain(truth[0], odometry), odometry);
  add_exact_closures(graph, truth);
  const Pose2 lonely{7.0, -3.0, 0.5};
  const std::size_t isolated = graph.add_node(lonely);
  graph.set_fixed(0, false);
  const OptimizeSummary summary = graph.optimize();
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  EXPECT_EQ(graph.poses()[isolated], lonely);
  double worst = 0.0;  // relative poses against the truth's
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose2 got = relative(graph.poses()[0], graph.poses()[i]);
    const Pose2 want = relative(truth[0], truth[i]);
    worst = std::max(worst, std::hypot(got.x - want.x, got.y - want.y));
  }
  std::printf(
      "[optimization] no fixed node: %d iterations, cost %.4g -> %.4g, relative error "
      "%.5f m\n",
      summary.iterations, summary.initial_cost, summary.final_cost, worst);
  EXPECT_LT(worst, 5e-3);
}

// The same graph gives the same poses and summary, bit for bit.
TEST(PoseGraph, Deterministic) {
  const std::vector<Pose2> truth = square_truth(10);
  const std::vector<Pose2> odometry = noisy_odometry(truth, 5);
  std::vector<std::vector<Pose2>> results;
  std::vector<OptimizeSummary> summaries;
  for (int run = 0; run < 2; ++run) {
    PoseGraph graph = odometry_graph(chain(truth[0], odometry), odometry);
    add_exact_closures(graph, truth);
    summaries.push_back(graph.optimize());
    results.push_back(graph.poses());
  }
  EXPECT_EQ(results[0], results[1]);
  EXPECT_EQ(summaries[0].iterations, summaries[1].iterations);
  EXPECT_EQ(summaries[0].final_cost, summaries[1].final_cost);
}

}  // namespace
