#include "slamkit/filters/graph/loop_groups.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "slamkit/filters/graph/loop_closure.hpp"

namespace slamkit::loop_groups_test {
namespace {

constexpr int kLap = 80;     // a 20 m square, a node a metre
constexpr int kNodes = 100;  // a lap and a quarter: nodes 80–99 drive over nodes 0–19 again

Pose2 Truth(int i) {
  Pose2 pose;
  for (int k = 0; k < i; ++k) pose = pose.Compose(Pose2(1.0, 0.0, (k % 20 == 19) ? M_PI / 2 : 0.0));
  return pose;
}

// The chain's edges measure the truth with a heading bias of 0.004 rad a node, σ as the graph
// back end's defaults: after the lap the chain is metres off, and stiff.
PoseGraph Chain(std::vector<Pose2>* dead_reckoning) {
  PoseGraph graph;
  dead_reckoning->assign(1, Pose2());
  for (int i = 0; i < kNodes; ++i) {
    if (i > 0) {
      const Pose2 step = Truth(i - 1).Between(Truth(i)).Compose(Pose2(0.0, 0.0, 0.004));
      graph.edges.push_back({i - 1, i, step, DiagonalInformation(0.01, 0.0025)});
      dead_reckoning->push_back(dead_reckoning->back().Compose(step));
    }
    graph.vertices.push_back({i, (*dead_reckoning)[static_cast<std::size_t>(i)]});
  }
  return graph;
}

// A closure from `anchor` to `node` measuring `error` composed onto the truth.
PoseGraphEdge Closure(int anchor, int node, const Pose2& error = Pose2()) {
  return {anchor, node, Truth(anchor).Between(Truth(node)).Compose(error),
          DiagonalInformation(0.05, 0.01)};
}

PoseGraphOptimizerParams Dcs() {
  PoseGraphOptimizerParams params;
  params.max_iterations = 200;
  params.loop_closure_loss = {.kind = RobustLossKind::kDcs, .scale = 9.0};
  return params;
}

// Whether two solutions are the same to the bit.
bool Same(const std::vector<Pose2>& a, const std::vector<Pose2>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](const Pose2& p, const Pose2& q) { return p.vector() == q.vector(); });
}

double MaxError(const std::vector<Pose2>& poses) {
  double worst = 0.0;
  for (int i = 0; i < kNodes; ++i) {
    worst = std::max(worst, (poses[static_cast<std::size_t>(i)].translation() - Truth(i).translation()).norm());
  }
  return worst;
}

// Six true closures of the second pass over the start, metres off the dead reckoning, and one
// false closure among them: DCS alone discounts them all and the loop stays open; the group of
// the six (not the false one) shuts it, and the false one still disagrees.
TEST(LoopGroups, AGroupOfAgreeingClosuresShutsALoopTheLossKeptOpen) {
  std::vector<Pose2> dead_reckoning;
  PoseGraph graph = Chain(&dead_reckoning);
  const int first_closure = static_cast<int>(graph.edges.size());
  for (int k = 0; k < 6; ++k) graph.edges.push_back(Closure(2 * k, kLap + 2 * k));
  graph.edges.push_back(Closure(40, kLap + 5, Pose2(3.0, -2.0, 1.0)));  // false
  ASSERT_GT(MaxError(dead_reckoning), 3.0);

  const PoseGraphSolution plain = OptimizePoseGraph(graph, dead_reckoning, Dcs());
  EXPECT_GT(MaxError(plain.poses), 2.0);
  const LoopGroupParams params;
  const std::vector<std::vector<int>> groups = ConsistentLoopGroups(graph, plain.poses, params);
  ASSERT_EQ(groups.size(), 1u);
  std::vector<int> group = groups.front();
  std::sort(group.begin(), group.end());
  EXPECT_EQ(group, (std::vector<int>{first_closure, first_closure + 1, first_closure + 2,
                                     first_closure + 3, first_closure + 4, first_closure + 5}));

  const PoseGraphSolution shut = OptimizeWithLoopGroups(graph, dead_reckoning, Dcs(), params);
  EXPECT_LT(MaxError(shut.poses), 1.0);  // the bias left inside the lap: 0.58 m
  for (int k = 0; k < 6; ++k) {
    EXPECT_TRUE(ClosureAgrees(graph.edges[static_cast<std::size_t>(first_closure + k)], shut.poses,
                              params.agreement_chi2));
  }
  EXPECT_FALSE(ClosureAgrees(graph.edges.back(), shut.poses, params.agreement_chi2));
  LoopGroupParams off;
  off.min_size = 0;
  EXPECT_TRUE(Same(OptimizeWithLoopGroups(graph, dead_reckoning, Dcs(), off).poses, plain.poses));
}

// Three false closures that agree with one another (a look-alike place, 3 m along) against
// twelve true ones a solution from the truth agrees with: the group is tried and not kept, since
// fewer closures agree once it is shut.
TEST(LoopGroups, AGroupThatMakesOtherClosuresDisagreeIsNotKept) {
  std::vector<Pose2> dead_reckoning;
  PoseGraph graph = Chain(&dead_reckoning);
  for (int k = 0; k < 12; ++k) graph.edges.push_back(Closure(k, kLap + k));
  for (int k = 0; k < 3; ++k) graph.edges.push_back(Closure(40 + k, kLap + 15 + k, Pose2(3, 0, 0)));
  std::vector<Pose2> truth;
  for (int i = 0; i < kNodes; ++i) truth.push_back(Truth(i));
  const PoseGraphSolution plain = OptimizePoseGraph(graph, truth, Dcs());
  ASSERT_LT(MaxError(plain.poses), 1.0);
  const LoopGroupParams params;
  ASSERT_EQ(ConsistentLoopGroups(graph, plain.poses, params).size(), 1u);
  const PoseGraphSolution tried = OptimizeWithLoopGroups(graph, truth, Dcs(), params);
  EXPECT_TRUE(Same(tried.poses, plain.poses));
}

}  // namespace
}  // namespace slamkit::loop_groups_test
