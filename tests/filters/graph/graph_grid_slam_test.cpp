#include "slamkit/filters/graph/graph_grid_slam.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "common/synthetic_room.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/optim/pose_graph_optimizer.hpp"

namespace slamkit::graph_grid_slam_test {
namespace {

using testing::RoomScan;

// Three laps of a 10 m × 4 m rectangle in the room, odometry 3 % long and turning 2 % too far
// plus 0.004 rad a step: after the laps raw odometry is metres off.
std::vector<LaserScan> LapsLog(std::vector<Pose2>* truth) {
  std::vector<LaserScan> log;
  Pose2 pose(-5, -3, 0.0), odometry;
  for (int k = 0; k < 3 * 68; ++k) {
    const double turn = (k % 34 >= 24) ? M_PI / 20 : 0.0;  // 24 steps straight, 90° in 10
    const Pose2 step(turn > 0 ? 0.05 : 0.25, 0.0, turn);
    pose = pose.Compose(step);
    odometry = odometry.Compose(Pose2(step.x() * 1.03, 0.0, step.theta() * 1.02 + 0.004));
    truth->push_back(pose);
    log.push_back(RoomScan(pose, 0.1 * k, odometry));
  }
  return log;
}

GraphGridSlamParams SmallGraph() {
  GraphGridSlamParams params;
  params.submaps.nodes_per_submap = 15;
  params.optimize_every_nodes = 10;
  params.loop.node_stride = 3;
  return params;
}

Trajectory RunGraph(const std::vector<LaserScan>& log, const GraphGridSlamParams& params, int threads,
               GridSlamStats* stats = nullptr, PoseGraph* graph = nullptr,
               std::vector<int>* node_scans = nullptr) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  GraphGridSlam slam(params);
  for (int k = 0; k < static_cast<int>(log.size()); ++k) {
    if (slam.ProcessScan(log[k]) && node_scans) node_scans->push_back(k);
  }
  slam.Finish();
  if (stats) *stats = slam.Stats();
  if (graph) *graph = *slam.FinalGraph();
  return slam.BestTrajectory();
}

// The largest error of the positions relative to the first pose.
double MaxError(const std::vector<Pose2>& truth, const std::vector<Pose2>& path) {
  double worst = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Pose2 t = truth.front().Between(truth[k]), p = path.front().Between(path[k]);
    worst = std::max(worst, (t.translation() - p.translation()).norm());
  }
  return worst;
}

TEST(SubmapStack, StartsEveryNNodesAndFinishesAfterTwiceN) {
  SubmapStack stack({.nodes_per_submap = 3}, OccupancyGridParams{}, ScanInsertionParams{});
  EXPECT_EQ(stack.MatchingSubmap(), nullptr);
  std::vector<int> finished_at;
  for (int node = 0; node < 10; ++node) {
    for (const auto& s : stack.Insert(node, Pose2(0.3 * node, 0, 0), RoomScan(Pose2(0.3 * node, 0, 0)))) {
      EXPECT_EQ(s->nodes.size(), 6u);
      EXPECT_EQ(s->origin_node, 3 * s->index);
      finished_at.push_back(node);
    }
    // The oldest active submap: 0 until node 5 finishes it, then 1, ...
    EXPECT_EQ(stack.MatchingSubmap()->index, node < 5 ? 0 : node < 8 ? 1 : 2) << node;
  }
  EXPECT_EQ(finished_at, (std::vector<int>{5, 8}));
  EXPECT_EQ(stack.all().size(), 4u);  // started at nodes 0, 3, 6 and 9
  EXPECT_EQ(stack.FinishAll().size(), 2u);
}

// Four finished submaps of ten nodes each (1 m apart); the search starts at node 50. Along the
// chain, submap k is 50 − (10 k + 19) m back; a closure from node 45 (in submap 3) to submap 0
// ties 0 to 3, so 0 is then 1 m away and 1 is 11 m away (through 0), not 21.
TEST(LoopClosureSearch, DriftDistancesFollowTheChainAndTheClosures) {
  LoopSearchInput input;
  input.nodes = {50};
  input.nodes_per_submap = 10;
  for (int i = 0; i <= 50; ++i) input.driven_m.push_back(i);
  for (int k = 0; k < 4; ++k) {
    auto s = std::make_shared<Submap>();
    s->index = k;
    s->origin_node = 10 * k;
    for (int i = 10 * k; i < 10 * k + 20; ++i) s->nodes.push_back(i);
    input.submaps.push_back(s);
  }
  EXPECT_EQ(DriftDistances(input), (std::vector<double>{31, 21, 11, 1}));
  input.closures.push_back({.node = 45, .submap = 0, .anchor_node = 0, .relative = Pose2(), .score = 1.0});
  EXPECT_EQ(DriftDistances(input), (std::vector<double>{1, 11, 11, 1}));
}

// A submap of the room's scans from a short path; a node's scan from a pose near it, its
// estimate 0.5 m and 0.08 rad off: the closure gives the node's true pose in the frame of the
// submap's node nearest to it (to about half a cell), and none when the truth is outside the
// window.
TEST(LoopClosureSearch, FindsTheTruePoseFromAnEstimateOffByHalfAMetre) {
  LoopSearchInput input;
  input.nodes_per_submap = 100;
  auto submap = std::make_shared<Submap>();
  submap->grid = OccupancyGrid(OccupancyGridParams{});
  submap->origin = Pose2(-4, -2, 0.3);
  for (int i = 0; i < 8; ++i) {
    const Pose2 pose = submap->origin.Compose(Pose2(0.3 * i, 0.0, 0.05 * i));
    InsertScan(submap->grid, pose, RoomScan(pose));
    submap->nodes.push_back(i);
    submap->poses.push_back(pose);
    input.global.push_back(pose);
    input.driven_m.push_back(0.3 * i);
  }
  submap->finished = true;
  input.submaps.push_back(submap);
  const Pose2 truth(-2.5, -1.0, 0.9);
  const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, ScanMatcherParams{});
  input.nodes = {8};
  input.points = {std::make_shared<const ScanPoints>(points)};
  input.global.push_back(truth.Compose(Pose2(0.4, -0.3, 0.08)));
  input.driven_m.push_back(5.0);
  LoopClosureParams params;
  params.matcher.min_score = 0.45;  // a submap of eight scans: its walls' cells are not yet sure
  params.base_linear_window_m = 0.6;
  params.base_angular_window_rad = 0.12;
  const std::vector<LoopClosure> found = SearchLoopClosures(input, params);
  ASSERT_EQ(found.size(), 1u);
  // Tied to the submap's node nearest to the match (node 6, 0.52 m away; node 5: 0.56 m), in
  // whose frame the closure gives the true pose.
  EXPECT_EQ(found[0].anchor_node, 6);
  const Pose2 expected = submap->poses[6].Between(truth);
  // Within about half a cell: the walls are only known to their cells.
  EXPECT_LT((found[0].relative.translation() - expected.translation()).norm(), 0.03);
  EXPECT_LT(std::abs(found[0].relative.theta() - expected.theta()), 0.01);
  // A room constrains every direction: the closure's edge has its σ in all three.
  EXPECT_TRUE(found[0].keep.isIdentity());
  EXPECT_EQ(LoopClosureEdge(found[0], params).information,
            DiagonalInformation(params.sigma_xy_m, params.sigma_theta_rad));
  params.base_linear_window_m = 0.2;  // the true pose outside the window: no closure
  params.linear_window_growth = 0.0;
  params.matcher.min_score = 0.8;
  EXPECT_TRUE(SearchLoopClosures(input, params).empty());
}

// Laps with drifting odometry: the graph's path stays within 10 cm of the truth where raw
// odometry is metres off, with loop closures found and the graph holding them; the same output
// for one thread and two.
TEST(GraphGridSlam, ClosesLapsWhereOdometryDriftsAndIsDeterministic) {
  std::vector<Pose2> truth;
  const std::vector<LaserScan> log = LapsLog(&truth);
  GridSlamStats stats;
  PoseGraph graph;
  const Trajectory path = RunGraph(log, SmallGraph(), 1, &stats, &graph);
  ASSERT_EQ(path.size(), log.size());
  std::vector<Pose2> estimate, odometry;
  for (std::size_t k = 0; k < log.size(); ++k) {
    estimate.push_back(path[k].pose);
    odometry.push_back(log[k].odometry);
  }
  EXPECT_GT(MaxError(truth, odometry), 1.0);
  EXPECT_LT(MaxError(truth, estimate), 0.1);
  ASSERT_TRUE(stats.graph.has_value());
  EXPECT_GT(stats.graph->loop_closures, 10);
  EXPECT_EQ(static_cast<int>(graph.vertices.size()), stats.graph->nodes);
  EXPECT_EQ(static_cast<int>(graph.edges.size()), stats.graph->nodes - 1 + stats.graph->loop_closures);
  const Trajectory again = RunGraph(log, SmallGraph(), 2);
  for (std::size_t k = 0; k < path.size(); ++k) EXPECT_EQ(again[k].pose.vector(), path[k].pose.vector());
}

// dense_max_correction_m: a dense scan's match that moves the odometry guess further than the
// limit is not taken. Below the odometry's error per step (7.5 mm) every match is refused and the
// front end is the odometry; above it the matches hold the laps (no loop closures in either run).
TEST(GraphGridSlam, DenseMatchMovingTheGuessTooFarKeepsTheOdometry) {
  std::vector<Pose2> truth;
  std::vector<LaserScan> log = LapsLog(&truth);
  log.resize(2 * 68);  // two laps: raw odometry is already 2.8 m off
  truth.resize(log.size());
  std::vector<Pose2> odometry;
  for (const LaserScan& scan : log) odometry.push_back(scan.odometry);
  GraphGridSlamParams params = SmallGraph();
  params.loop.matcher.min_score = 1.0;  // no closures: the front end alone
  const auto poses = [&](double limit_m) {
    params.dense_max_correction_m = limit_m;
    GridSlamStats stats;
    const Trajectory path = RunGraph(log, params, 1, &stats);
    EXPECT_EQ(stats.graph->loop_closures, 0);
    // Every scan after the first is matched once: refused, or taken without a rescue here.
    const int kept = limit_m < 1e-3 ? static_cast<int>(log.size()) - 1 : 0;
    EXPECT_EQ(stats.graph->matches_kept_odometry, kept);
    EXPECT_EQ(stats.graph->matches_rescued, 0);
    std::vector<Pose2> out;
    for (const auto& p : path) out.push_back(p.pose);
    return out;
  };
  const std::vector<Pose2> refused = poses(1e-4);
  EXPECT_LT(MaxError(odometry, refused), 1e-9);
  const std::vector<Pose2> taken = poses(0.2);
  EXPECT_GT(MaxError(odometry, taken), 1.0);
  EXPECT_LT(MaxError(truth, taken), 0.3);  // 0.10 m: the front end alone drifts a little
}

// The RMS position error of `poses` against `truth`, both relative to their first pose.
double RmsError(const std::vector<Pose2>& truth, const std::vector<Pose2>& poses) {
  double sum = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const Pose2 t = truth.front().Between(truth[k]), p = poses.front().Between(poses[k]);
    sum += (t.translation() - p.translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(truth.size()));
}

// The graph a run recorded, with false closures added (10 % of its closures, between random
// nodes, random measurements): optimised with the back end's loss from the front end's chain, its
// nodes stay within 5 % of the clean graph's error, where the plain squared loss is torn.
TEST(GraphGridSlam, FalseClosuresInARecordedGraphDoNotTearIt) {
  std::vector<Pose2> truth;
  const std::vector<LaserScan> log = LapsLog(&truth);
  GridSlamStats stats;
  PoseGraph graph;
  std::vector<int> node_scans;
  const GraphGridSlamParams params = SmallGraph();
  RunGraph(log, params, 2, &stats, &graph, &node_scans);
  ASSERT_EQ(node_scans.size(), graph.vertices.size());
  std::vector<Pose2> node_truth, chain = {Pose2()};
  for (const int k : node_scans) node_truth.push_back(truth[static_cast<std::size_t>(k)]);
  for (std::size_t i = 1; i < graph.vertices.size(); ++i) {
    chain.push_back(chain.back().Compose(graph.edges[i - 1].measurement));  // edges i-1 → i first
  }
  PoseGraph corrupted = graph;
  Rng rng(3);
  const int n = static_cast<int>(graph.vertices.size());
  for (int k = 0; k < stats.graph->loop_closures / 10; ++k) {
    const int i = static_cast<int>(rng.Uniform(0, n - 20));
    const int j = i + 10 + static_cast<int>(rng.Uniform(0, n - i - 10));
    corrupted.edges.push_back({i, j, Pose2(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-3, 3)),
                               graph.edges.back().information});
  }
  PoseGraphOptimizerParams robust;
  robust.loop_closure_loss = params.loop_loss;
  const auto error = [&](const PoseGraph& g, const PoseGraphOptimizerParams& p) {
    return RmsError(node_truth, OptimizePoseGraph(g, chain, p).poses);
  };
  const double clean = error(graph, robust);
  EXPECT_LT(clean, 0.1);
  EXPECT_LT(error(corrupted, robust), 1.05 * clean);
  EXPECT_GT(error(corrupted, PoseGraphOptimizerParams{}), 2.0 * clean);
}

}  // namespace
}  // namespace slamkit::graph_grid_slam_test
