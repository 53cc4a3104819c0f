// Issue 8, items 1, 4, 5 and 12: bad grid runs fail early with an InputError (exit code 2 in the
// command line) instead of crashing or allocating until the process dies.
#include "slamkit/runners/grid/grid_run.hpp"

#include <gtest/gtest.h>

#include "common/synthetic_room.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

GridSlamConfig SmallParams() {
  GridSlamConfig config;
  config.rbpf.particles = 3;
  return config;
}

CarmenLog TwoScanLog(const Pose2& second_odometry, const Pose2& laser_offset = Pose2()) {
  CarmenLog log;
  log.scans.push_back(testing::RoomScan(Pose2(), 0.0, Pose2()));
  log.scans.push_back(testing::RoomScan(Pose2(), 0.1, second_odometry));
  for (LaserScan& s : log.scans) s.laser_offset = laser_offset;
  return log;
}

TEST(GridRunLimits, ALogWithNoScanIsAnInputError) {
  EXPECT_THROW(RunGridSlam(CarmenLog{}, SmallParams()), InputError);
}

TEST(GridRunLimits, HugePosesAndOffsetsAreInputErrors) {
  EXPECT_THROW(RunGridSlam(TwoScanLog(Pose2(1e308, 0.0, 0.0)), SmallParams()), InputError);
  EXPECT_THROW(RunGridSlam(TwoScanLog(Pose2(), Pose2(1e300, 0.0, 0.0)), SmallParams()),
               InputError);
}

TEST(GridRunLimits, MapsBeyondTheLimitsFailEarly) {
  // An odometry jump of 1e4 m on both axes: a map of 200000² cells.
  EXPECT_THROW(RunGridSlam(TwoScanLog(Pose2(1e4, 1e4, 0.0)), SmallParams()), InputError);
  GridSlamConfig fine = SmallParams();
  fine.rbpf.grid.resolution_m = 1e-9;
  EXPECT_THROW(RunGridSlam(TwoScanLog(Pose2()), fine), InputError);
  fine.rbpf.grid.resolution_m = 1e-4;  // item 12: a room of ~10 m is 1e10 cells, beyond max_cells
  EXPECT_THROW(RunGridSlam(TwoScanLog(Pose2()), fine), InputError);
  GridSlamConfig bad = SmallParams();
  bad.rbpf.grid.resolution_m = 0.0;
  EXPECT_THROW(RunGridSlam(TwoScanLog(Pose2()), bad), InputError);
}

TEST(GridRunLimits, ANormalRunStillWorks) {
  const GridRunResult r = RunGridSlam(TwoScanLog(Pose2(0.5, 0.0, 0.0)), SmallParams());
  EXPECT_EQ(r.scans, 2);
  EXPECT_EQ(r.trajectory.size(), 2u);
}

}  // namespace
}  // namespace slamkit
