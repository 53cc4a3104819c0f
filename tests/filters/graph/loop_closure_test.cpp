#include "slamkit/filters/graph/loop_closure.hpp"

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit::loop_closure_test {
namespace {

// A straight corridor along x, 2.05 m wide, mapped by a submap of scans a metre apart: a scan in
// it pins the sideways position and the heading, and nothing within 8 m says where along it.
class CorridorClosureTest : public ::testing::Test {
 protected:
  CorridorClosureTest() {
    laser_.sigma_range_m = 0.0;
    auto submap = std::make_shared<Submap>();
    submap->grid = OccupancyGrid(OccupancyGridParams{});
    ScanInsertionParams insertion;
    insertion.usable_range_m = kRangeM;
    for (int i = 0; i <= 12; ++i) {
      const Pose2 pose(i, 0.0, 0.0);
      InsertScan(submap->grid, pose, Scan(pose), insertion);
      submap->nodes.push_back(i);
      submap->poses.push_back(pose);
      input_.global.push_back(pose);
      input_.driven_m.push_back(i);
    }
    submap->origin = submap->poses.front();
    submap->finished = true;
    input_.submaps.push_back(submap);
    input_.nodes_per_submap = 100;
  }
  LaserScan Scan(const Pose2& pose) {
    Rng rng(1);
    return SimulateScan(corridor_, pose, laser_, rng);
  }
  // The closures of node 13, whose scan is taken at `truth` and whose estimate is `estimate`.
  std::vector<LoopClosure> Search(const Pose2& truth, const Pose2& estimate) {
    input_.nodes = {13};
    input_.points = {std::make_shared<const ScanPoints>(
        PrepareScan(Scan(truth), kRangeM, params_.refinement))};
    input_.global.push_back(estimate);
    input_.driven_m.push_back(20.0);
    return SearchLoopClosures(input_, params_);
  }

  static constexpr double kRangeM = 8.0;
  const FloorPlan corridor_{{{{-2.0, -1.025}, {40.0, -1.025}}, {{-2.0, 1.025}, {40.0, 1.025}}}};
  LaserSimParams laser_;
  LoopSearchInput input_;
  LoopClosureParams params_;
};

// The closure holds the node across the corridor and in heading, as measured, and its edge lets
// it move along the corridor almost freely: there the match is where the search stopped.
TEST_F(CorridorClosureTest, HoldsOnlyAcrossTheCorridor) {
  const Pose2 truth(5.3, 0.1, 0.05);
  const std::vector<LoopClosure> found = Search(truth, truth.Compose(Pose2(0.3, -0.2, 0.04)));
  ASSERT_EQ(found.size(), 1u);
  const LoopClosure& c = found[0];
  const Pose2 measured = input_.global[static_cast<std::size_t>(c.anchor_node)].Compose(c.relative);
  EXPECT_NEAR(measured.y(), truth.y(), 0.03);
  EXPECT_NEAR(measured.theta(), truth.theta(), 0.015);
  // The corridor's axis and its normal in the node's frame (it heads 0.05 rad off the axis).
  const double th = measured.theta();
  const Eigen::Vector3d along(std::cos(th), -std::sin(th), 0.0);
  const Eigen::Vector3d across(std::sin(th), std::cos(th), 0.0);
  EXPECT_LT((c.keep * along).norm(), 0.05);
  EXPECT_GT((c.keep * across).norm(), 0.95);
  const Eigen::Matrix3d info = LoopClosureEdge(c, params_).information;
  const double cost_along = 0.25 * along.dot(info * along);  // 0.5 m along, and across
  const double cost_across = 0.25 * across.dot(info * across);
  EXPECT_LT(cost_along, 0.01 * cost_across);
  EXPECT_GT(cost_across, 0.9 * 0.25 / (params_.sigma_xy_m * params_.sigma_xy_m));
}

}  // namespace
}  // namespace slamkit::loop_closure_test
