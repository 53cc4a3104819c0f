// The closed loop of SPEC S2: simulation, filter and planner interleaved.
#include "slamkit/runners/landmark/active_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

ScenarioConfig LoadShipped(const char* name) {
  return LoadScenario(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / name);
}

TEST(ActiveRun, RoutePlannerReproducesTheOpenLoopRun) {
  const ScenarioConfig c = LoadShipped("swslam.yaml");
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  Rng noise(3), order(1003);
  const SimRun sim = Simulate(c.scenario, world, noise, order);
  const std::unique_ptr<LandmarkSlamFilter> filter = EkfSlamFactory(c)();
  const RunResult open = RunLandmarkFilter(*filter, sim, world, c.scenario.dt_s, false);
  PlannerConfig planner = c.planner;
  planner.kind = PlannerKind::kRoute;
  const std::unique_ptr<LandmarkSlamFilter> closed_filter = EkfSlamFactory(c)();
  Rng closed_noise(3), closed_order(1003), planner_rng(2003);
  const ActiveRunResult closed = RunActive(c.scenario, planner, world, *closed_filter, false,
                                           closed_noise, closed_order, planner_rng);
  const RunResult& r = closed.run;
  ASSERT_EQ(r.estimate.size(), open.estimate.size());
  for (std::size_t k = 0; k < open.estimate.size(); ++k) {
    ASSERT_EQ(r.truth[k].pose.vector(), open.truth[k].pose.vector()) << k;
    ASSERT_EQ(r.estimate[k].pose.vector(), open.estimate[k].pose.vector()) << k;
  }
  EXPECT_EQ(r.nees, open.nees);
  EXPECT_EQ(r.rmse.position_m, open.rmse.position_m);
  EXPECT_EQ(r.map_rmse_m, open.map_rmse_m);
  EXPECT_EQ(r.association.correct, open.association.correct);
  EXPECT_EQ(r.association.sightings, open.association.sightings);
  ASSERT_EQ(r.map.landmarks.size(), open.map.landmarks.size());
  for (std::size_t i = 0; i < r.map.landmarks.size(); ++i) {
    EXPECT_EQ(r.map.landmarks[i].position_m, open.map.landmarks[i].position_m);
    EXPECT_EQ(r.map.landmarks[i].source_id, open.map.landmarks[i].source_id);
  }
  // The route run detects areas of interest (its sections) but never leaves the route.
  EXPECT_TRUE(closed.centres_m.empty());
  EXPECT_FALSE(closed.sections.empty());
}

TEST(ActiveRun, SectionStatsCountTheSectionsPeriodsOnly) {
  const std::vector<std::vector<LandmarkId>> periods = {{1, 2}, {1, 2, 3}, {3}, {4, 5, 6, 7}};
  RouteSection section;
  section.first_period = 1;
  section.end_period = 3;  // periods 1 and 2
  const SectionStats s = ComputeSectionStats(section, periods);
  EXPECT_EQ(s.periods, 2);
  EXPECT_EQ(s.observations, 4);
  EXPECT_EQ(s.landmarks, 3);
  EXPECT_DOUBLE_EQ(s.observations_per_period, 2.0);
  EXPECT_DOUBLE_EQ(s.observations_per_landmark, 4.0 / 3.0);
  section.end_period = -1;  // open: to the end of the run
  const SectionStats open = ComputeSectionStats(section, periods);
  EXPECT_EQ(open.periods, 3);
  EXPECT_EQ(open.observations, 8);
  EXPECT_EQ(open.landmarks, 7);
}

}  // namespace
}  // namespace slamkit
