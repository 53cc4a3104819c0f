// Issue 27, part 5: the grid runner takes any GridSlam, and the config's back end through
// MakeGridSlam.
#include <gtest/gtest.h>

#include <stdexcept>

#include "common/synthetic_room.hpp"
#include "slamkit/filters/grid_slam_factory.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/grid/grid_run.hpp"

namespace slamkit {
namespace {

CarmenLog RoomLog(int scans) {
  CarmenLog log;
  for (int i = 0; i < scans; ++i) {
    log.scans.push_back(testing::RoomScan(Pose2(0.1 * i, 0.0, 0.0), 0.1 * i,
                                          Pose2(0.1 * i, 0.02 * i, 0.0)));
  }
  return log;
}

// A back end that is not the RBPF: it places each scan at its odometry, updates on every
// second scan and can be told to fail its health check.
class OdometryGridSlam final : public GridSlam {
 public:
  explicit OdometryGridSlam(bool healthy) : healthy_(healthy), map_(OccupancyGridParams{}) {}
  bool ProcessScan(const LaserScan& scan) override {
    path_.push_back({scan.t_s, scan.odometry});
    return path_.size() % 2 == 0;
  }
  Pose2 CurrentPose() override { return path_.back().pose; }
  Trajectory BestTrajectory() override { return path_; }
  const OccupancyGrid& BestMap() const override { return map_; }
  GridSlamStats Stats() const override {
    return {.updates = static_cast<int>(path_.size()) / 2, .resamples = 7,
            .heading_drift_in_use_rad_per_m = 0.25, .graph = std::nullopt};
  }
  void CheckOutputHealth() const override {
    if (!healthy_) ThrowNumericalError("OdometryGridSlam at output", "made to fail");
  }

 private:
  bool healthy_;
  OccupancyGrid map_;
  Trajectory path_;
};

TEST(GridSlamInterface, TheRunnerTakesAnyBackEnd) {
  const CarmenLog log = RoomLog(5);
  OdometryGridSlam slam(true);
  int last_progress = 0;
  const GridRunResult r = RunGridSlam(log, slam, [&](int done, int) { last_progress = done; });
  ASSERT_EQ(r.trajectory.size(), 5u);
  EXPECT_EQ(r.trajectory[4].pose.y(), log.scans[4].odometry.y());
  EXPECT_EQ(r.scans, 5);
  EXPECT_EQ(r.updates, 2);
  EXPECT_EQ(r.resamples, 7);
  EXPECT_EQ(r.heading_drift_in_use_rad_per_m, 0.25);
  EXPECT_EQ(last_progress, 5);
}

TEST(GridSlamInterface, AnUnhealthyBackEndIsANumericalErrorNotAnInputError) {
  OdometryGridSlam slam(false);
  EXPECT_THROW(RunGridSlam(RoomLog(3), slam), NumericalError);
}

TEST(GridSlamInterface, TheFactoryMakesTheRbpfTheConfigNames) {
  GridSlamConfig config;
  config.rbpf.particles = 4;
  config.rbpf.linear_update_m = 0.05;
  const CarmenLog log = RoomLog(8);
  const GridRunResult through_factory = RunGridSlam(log, config);
  RbpfGridSlam direct(config.rbpf);
  const GridRunResult by_hand = RunGridSlam(log, direct);
  ASSERT_EQ(through_factory.trajectory.size(), by_hand.trajectory.size());
  for (std::size_t i = 0; i < by_hand.trajectory.size(); ++i) {
    EXPECT_EQ(through_factory.trajectory[i].pose.vector(), by_hand.trajectory[i].pose.vector());
  }
  EXPECT_GT(by_hand.updates, 0);
  EXPECT_EQ(through_factory.updates, by_hand.updates);
  EXPECT_EQ(through_factory.resamples, by_hand.resamples);
}

TEST(GridSlamInterface, TheFactoryRefusesParamsTheFilterCannotTake) {
  GridSlamConfig config;
  config.rbpf.grid.resolution_m = 0.0;
  EXPECT_THROW(MakeGridSlam(config), std::invalid_argument);
  EXPECT_THROW(RunGridSlam(RoomLog(2), config), InputError);
}

}  // namespace
}  // namespace slamkit
