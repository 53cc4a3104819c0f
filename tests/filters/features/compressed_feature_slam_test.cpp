// Compressed updates (Guivant & Nebot 2001) in the line-and-corner EKF-SLAM of SPEC S1: driven
// through the office world beside the dense filter, the same decisions on every scan and the same
// state and covariance after every global update (issue 32, part 1, for every landmark kind).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <memory>
#include <string>

#include "filters/compressed_circle.hpp"
#include "slamkit/features/scan_features.hpp"
#include "slamkit/filters/features/feature_ekf_slam.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/sim/laser_sim.hpp"
#include "slamkit/sim/maze_route.hpp"

namespace slamkit {
namespace {

using testing::ExpectSameDecisions;
using testing::RelativeDiff;

// The serpentine route through every corridor of a maze of 5 × 5 blocks (walls and corners
// everywhere, 31 m across), a 10 m laser: walls leave the area and come back.
struct MazeRun {
  FloorPlan plan;
  GridSimRun sim;
};

const MazeRun& Route() {
  static const MazeRun run = [] {
    SquareMazeParams maze;
    maze.outer_size_m = 31.0;
    MazeRun r;
    r.plan = MakeSquareMaze(maze);
    GridSimParams params;
    params.route = MazeRoute(maze);
    params.speed_mps = 2.0;  // 0.2 m between scans
    params.laser.beams = 181;
    params.laser.range_limit_m = 10.0;
    params.laser.sigma_range_m = 0.01;
    Rng rng(2032);
    r.sim = SimulateGridRun(r.plan, params, RouteStartPose(params.route), rng);
    return r;
  }();
  return run;
}

std::unique_ptr<FeatureEkfSlam> MakeFilter(EkfUpdateMode update, const Pose2& start) {
  OdometryParams odometry;
  odometry.sigma_xy_m = 0.015;
  odometry.sigma_theta_rad = 0.006;
  FeatureEkfSlamParams params;
  params.update = update;
  params.area_reach_m = 10.0;  // the laser's
  params.corner_reach_m = 10.0;
  params.active_area.hysteresis_fraction = 0.3;
  CovarianceSelectionParams selection;
  selection.k_max = 3;
  auto slam = std::make_unique<FeatureEkfSlam>(params, std::make_unique<OdometryModel>(odometry),
                                               std::make_unique<SelectByCovariance>(selection));
  slam->Reset(start);
  return slam;
}

void ExpectSameState(const FeatureEkfSlam& got, const FeatureEkfSlam& expected,
                     const std::string& where) {
  ASSERT_EQ(got.ekf().StateSize(), expected.ekf().StateSize()) << where;
  EXPECT_LT(RelativeDiff(got.ekf().State(), expected.ekf().State()), 1e-9) << where;
  EXPECT_LT(RelativeDiff(got.ekf().Covariance(), expected.ekf().Covariance()), 1e-9) << where;
}

TEST(CompressedFeatureEkfSlam, EqualsTheDenseFilterAfterEveryGlobalUpdate) {
  const MazeRun& route = Route();
  const Pose2 start = route.sim.truth[0].pose;
  const auto dense = MakeFilter(EkfUpdateMode::kDense, start);
  const auto compressed = MakeFilter(EkfUpdateMode::kCompressed, start);
  LineExtractionParams extraction;
  extraction.max_usable_range_m = 10.0;
  extraction.sigma_range_m = 0.01;
  long global_updates = 0;
  int lines_in_areas = 0;  // lines started while an area was open, within and beyond its reach
  for (std::size_t k = 0; k < route.sim.scans.size(); ++k) {
    const LaserScan& scan = route.sim.scans[k];
    if (k > 0) {
      const Pose2 u = route.sim.scans[k - 1].odometry.Between(scan.odometry);
      dense->Predict(u.vector(), 0.1);
      compressed->Predict(u.vector(), 0.1);
    }
    const ScanFeatures features = ToRobotFrame(ExtractFeatures(scan, extraction), scan.laser_offset);
    const int lines_before = compressed->NumLines();
    const FeatureDecisions expected = dense->Update(features);
    const FeatureDecisions got = compressed->Update(features);
    const int step = static_cast<int>(k);
    ExpectSameDecisions(got.lines, expected.lines, step);
    ExpectSameDecisions(got.corners, expected.corners, step);
    if (compressed->ekf().IsCompressed()) lines_in_areas += compressed->NumLines() - lines_before;
    // Every fifth global update: each comparison synchronises a copy, O(n²·a).
    if (compressed->Compression().global_updates > global_updates) {
      global_updates = compressed->Compression().global_updates;
      if (global_updates % 5 == 0) {
        ExpectSameState(*compressed, *dense, "scan " + std::to_string(k));
      }
    }
    if (::testing::Test::HasFailure()) return;
  }
  compressed->Synchronise();
  ExpectSameState(*compressed, *dense, "at the end");
  EXPECT_GE(global_updates, 20);
  EXPECT_GT(lines_in_areas, 10);
  // The areas were parts of the map, not the whole of it.
  EXPECT_LT(compressed->Compression().max_active_size, 0.75 * compressed->ekf().StateSize());
  std::printf("%ld global updates, largest area %d of %d entries, %d lines, %d corners\n",
              global_updates, compressed->Compression().max_active_size,
              compressed->ekf().StateSize(), compressed->NumLines(), compressed->NumCorners());
  EXPECT_GT(compressed->NumCorners(), 20);
}

}  // namespace
}  // namespace slamkit
