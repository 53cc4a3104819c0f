#include "slamkit/optim/grid_scan_refinement.hpp"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace slamkit::grid_scan_refinement_test {
namespace {

constexpr double kRes = 0.05;
constexpr int kWidth = 120, kHeight = 80;  // a 6 m × 4 m room, walls on the border cells

// The room's walls run through the centres of its border cells, so that the map's occupied
// cells are not a rasterisation that is off the true wall by part of a cell.
OccupancyGrid Room() {
  OccupancyGrid map(OccupancyGridParams{kRes});
  for (int y = 0; y <= kHeight; ++y) {
    for (int x = 0; x <= kWidth; ++x) {
      const bool wall = x == 0 || y == 0 || x == kWidth || y == kHeight;
      map.Update({x, y}, wall ? 4.0f : -2.0f);
    }
  }
  return map;
}

// Where a laser at `pose` sees the walls, every 2° round, in the laser's frame.
std::vector<Eigen::Vector2d> ScanOfRoom(const Pose2& pose) {
  const double lo = 0.5 * kRes, x_hi = (kWidth + 0.5) * kRes, y_hi = (kHeight + 0.5) * kRes;
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 180; ++k) {
    const double a = pose.theta() + k * M_PI / 90.0;
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    double range = std::numeric_limits<double>::infinity();
    if (d.x() > 1e-9) range = std::min(range, (x_hi - pose.x()) / d.x());
    if (d.x() < -1e-9) range = std::min(range, (lo - pose.x()) / d.x());
    if (d.y() > 1e-9) range = std::min(range, (y_hi - pose.y()) / d.y());
    if (d.y() < -1e-9) range = std::min(range, (lo - pose.y()) / d.y());
    points.push_back(pose.TransformTo(pose.translation() + range * d));
  }
  return points;
}

// From a start off by less than a cell, the points alone (no pull towards the start) bring the
// pose to the truth far below the cell size: the interpolated map is smooth between cells.
TEST(GridScanRefinement, RecoversASubCellOffset) {
  const OccupancyGrid map = Room();
  const Pose2 truth(2.213, 1.778, 0.31);
  const std::vector<Eigen::Vector2d> scan = ScanOfRoom(truth);
  GridRefinementParams params;
  params.translation_weight = params.rotation_weight = 0.0;
  for (const Pose2& offset : {Pose2(0.02, -0.015, 0.01), Pose2(-0.018, 0.02, -0.012)}) {
    const Pose2 start(truth.x() + offset.x(), truth.y() + offset.y(),
                      truth.theta() + offset.theta());
    const Pose2 refined = RefinePoseOnGrid(map, scan, start, params);
    EXPECT_LT((refined.translation() - truth.translation()).norm(), 0.003);
    EXPECT_LT(std::abs(refined.theta() - truth.theta()), 0.001);
  }
}

// The weights on the move hold the pose: very large ones keep it at the start.
TEST(GridScanRefinement, LargeMoveWeightsKeepTheStart) {
  const OccupancyGrid map = Room();
  const Pose2 truth(2.213, 1.778, 0.31);
  const Pose2 start(2.233, 1.763, 0.32);
  GridRefinementParams params;
  params.translation_weight = params.rotation_weight = 1e6;
  const Pose2 refined = RefinePoseOnGrid(map, ScanOfRoom(truth), start, params);
  EXPECT_LT((refined.translation() - start.translation()).norm(), 1e-5);
  EXPECT_LT(std::abs(refined.theta() - start.theta()), 1e-5);
  EXPECT_EQ(RefinePoseOnGrid(map, {}, start).vector(), start.vector());
}

TEST(GridScanRefinement, RejectsBadParameters) {
  const OccupancyGrid map = Room();
  GridRefinementParams params;
  params.translation_weight = -1.0;
  EXPECT_THROW(RefinePoseOnGrid(map, {{1.0, 0.0}}, Pose2(), params), std::invalid_argument);
  params = {};
  params.unknown_probability = 1.5;
  EXPECT_THROW(RefinePoseOnGrid(map, {{1.0, 0.0}}, Pose2(), params), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit::grid_scan_refinement_test
