#include "slamkit/runners/localization/localize_run.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/io/grid_writers.hpp"
#include "slamkit/io/relations_reader.hpp"
#include "slamkit/runners/grid/grid_run.hpp"

namespace slamkit {
namespace {

// The Intel log's first 4,000 scans mapped by the grid filter (defaults, seed 1), its map as
// map_server's image, and the relations those scans cover.
struct IntelCase {
  CarmenLog log;
  GridRunResult grid;
  OccupancyImage map;
  std::vector<PoseRelation> relations;
};

const IntelCase* Intel() {
  static const std::unique_ptr<IntelCase> intel = []() -> std::unique_ptr<IntelCase> {
    const std::filesystem::path dir = std::filesystem::path(SLAMKIT_DATASETS_DIR) / "carmen";
    if (!std::filesystem::exists(dir / "intel.clf")) return nullptr;
    auto c = std::make_unique<IntelCase>();
    c->log = ReadCarmenLog(dir / "intel.clf");
    c->log.scans.resize(4000);
    c->grid = RunGridSlam(c->log, GridSlamConfig{});
    c->map = RenderOccupancyImage(c->grid.map);
    c->relations = RelationsCovered(c->grid.trajectory, ReadRelations(dir / "intel.relations"));
    return c;
  }();
  return intel.get();
}

// On the map the grid filter built, from its start pose, localisation is as precise as the
// filter that built the map. Measured (Release, 805 relations): grid 0.0244 m / 0.405°,
// localisation 0.0234 m / 0.391°; the bounds allow 10 % more. From no idea where the robot is,
// the particles over the whole free space settle on the tracked poses and say when. (One test:
// ctest runs each in a process of its own, and each would map the log again.)
TEST(LocalizeIntel, AsPreciseAsTheGridFilterAndFoundFromAGlobalStart) {
  const IntelCase* intel = Intel();
  if (intel == nullptr) GTEST_SKIP() << "no intel.clf";
  const LocalizationResult tracked =
      RunLocalization(intel->log, intel->map, LocalizationConfig{}, Pose2());
  const RelationErrorStats grid = EvaluateRelations(intel->grid.trajectory, intel->relations);
  const RelationErrorStats localised = EvaluateRelations(tracked.trajectory, intel->relations);
  std::printf("%d relations: grid %.4f m / %.3f deg, localisation %.4f m / %.3f deg\n",
              grid.count, grid.trans_mean_m, grid.rot_mean_deg, localised.trans_mean_m,
              localised.rot_mean_deg);
  EXPECT_GT(grid.count, 750);
  EXPECT_LT(localised.trans_mean_m, 1.1 * grid.trans_mean_m);
  EXPECT_LT(localised.rot_mean_deg, 1.1 * grid.rot_mean_deg);
  ASSERT_TRUE(tracked.settled_scan.has_value());
  EXPECT_LT(*tracked.settled_scan, 300);  // the robot stands still for its first ~140 scans
  EXPECT_GT(tracked.refined_scans, 3500);
  EXPECT_EQ(tracked.recovery_updates, 0);

  const LocalizationResult global =
      RunLocalization(intel->log, intel->map, LocalizationConfig{}, std::nullopt);
  ASSERT_TRUE(global.settled_scan.has_value());
  std::printf("global localisation settled at scan %d\n", *global.settled_scan);
  EXPECT_LT(*global.settled_scan, 1000);
  for (std::size_t i = *global.settled_scan + 50; i < intel->log.scans.size(); ++i) {
    ASSERT_LT((global.trajectory[i].pose.translation() - tracked.trajectory[i].pose.translation())
                  .norm(),
              0.3)
        << i;
  }
}

// The log cut after scan 1,500 and resumed at scan 2,500, its odometry carried on from scan
// 1,500's as if the robot had not moved: with the defaults (augmented MCL's random particles
// once the scans stop matching the map) the filter finds the robot again and says so, while on
// the uncut log it never draws one.
TEST(LocalizeIntel, RandomParticlesFindAKidnappedRobot) {
  const IntelCase* intel = Intel();
  if (intel == nullptr) GTEST_SKIP() << "no intel.clf";
  CarmenLog cut;
  cut.scans.assign(intel->log.scans.begin(), intel->log.scans.begin() + 1500);
  const Pose2 before = cut.scans.back().odometry;
  const Pose2 resumed = intel->log.scans[2500].odometry;
  for (std::size_t i = 2500; i < intel->log.scans.size(); ++i) {
    LaserScan scan = intel->log.scans[i];
    scan.odometry = before.Compose(resumed.Between(scan.odometry));
    cut.scans.push_back(scan);
  }
  ASSERT_GT((intel->grid.trajectory[1499].pose.translation() -
             intel->grid.trajectory[2500].pose.translation()).norm(),
            2.0);
  const LocalizationResult run = RunLocalization(cut, intel->map, LocalizationConfig{}, Pose2());
  ASSERT_TRUE(run.settled_scan.has_value());
  ASSERT_TRUE(run.last_recovery_scan.has_value());
  std::printf("kidnapped after scan 1500: %d updates drew random particles, the last at scan %d; "
              "settled at scan %d\n",
              run.recovery_updates, *run.last_recovery_scan, *run.settled_scan);
  EXPECT_GT(*run.settled_scan, 1500);
  const std::size_t end = cut.scans.size() - 1;
  EXPECT_LT((run.trajectory[end].pose.translation() -
             intel->grid.trajectory.back().pose.translation()).norm(),
            0.3);
}

}  // namespace
}  // namespace slamkit
