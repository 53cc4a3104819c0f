// The closed loop of SPEC S2: simulation, filter and planner interleaved.
#include "slamkit/runners/active_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "slamkit/runners/scenario_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

ScenarioConfig Load(const char* name) {
  return LoadScenario(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / name);
}

ActiveRunResult RunWith(const ScenarioConfig& c, PlannerKind kind, std::uint64_t seed) {
  PlannerConfig planner = c.planner;
  planner.kind = kind;
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  const std::unique_ptr<LandmarkSlamFilter> filter = EkfSlamFactory(c)();
  Rng noise(seed), order(seed + 1000), planner_rng(seed + 2000);
  return RunActive(c.scenario, planner, world, *filter, c.ekf.known_association(), noise, order,
                   planner_rng);
}

TEST(ActiveRun, RoutePlannerReproducesTheOpenLoopRun) {
  const ScenarioConfig c = Load("swslam.yaml");
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  Rng noise(3), order(1003);
  const SimRun sim = Simulate(c.scenario, world, noise, order);
  const std::unique_ptr<LandmarkSlamFilter> filter = EkfSlamFactory(c)();
  const RunResult open = RunLandmarkFilter(*filter, sim, world, c.scenario.dt_s, false);
  const ActiveRunResult closed = RunWith(c, PlannerKind::kRoute, 3);
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

// Observations per landmark over all of a run's sections together.
double ObservationsPerLandmark(const ActiveRunResult& r) {
  int observations = 0, landmarks = 0;
  for (const SectionStats& s : r.sections) {
    observations += s.observations;
    landmarks += s.landmarks;
  }
  return landmarks > 0 ? double(observations) / landmarks : 0.0;
}

void Print(const char* name, const ActiveRunResult& r) {
  double anees = 0.0;
  for (double v : r.run.nees) anees += v / static_cast<double>(r.run.nees.size());
  std::cout << name << ": steps " << r.run.errors.size() << ", periods " << r.periods
            << ", position RMS " << r.run.rmse.position_m << " m, heading RMS "
            << r.run.rmse.heading_rad << " rad, mean NEES " << anees << ", landmarks mapped " << r.run.map.landmarks.size()
            << ", association correct " << r.run.association.correct << "/"
            << r.run.association.sightings << "\n";
  for (const SectionStats& s : r.sections) {
    std::cout << "  section periods [" << s.section.first_period << ", " << s.section.end_period
              << ") to route waypoint " << s.section.route_waypoint;
    if (s.section.detour_m) {
      std::cout << " via (" << s.section.detour_m->x() << ", " << s.section.detour_m->y() << ")"
                << (s.section.detour_reached ? " reached" : " abandoned");
    }
    std::cout << ": observations " << s.observations << ", per period "
              << s.observations_per_period << ", landmarks " << s.landmarks << ", per landmark "
              << s.observations_per_landmark << "\n";
  }
}

// SPEC S2 / seed 001 Sec. 4.1: SWSLAM goes to the dense clusters and sees their landmarks more
// often than the route alone does, in the sections that follow an area of interest.
TEST(ActiveRun, SwslamVisitsAClusterCentreAndObservesLandmarksMoreOften) {
  const ScenarioConfig c = Load("swslam.yaml");
  ASSERT_EQ(c.planner.kind, PlannerKind::kSwslam);
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  for (std::uint64_t seed : {1, 2}) {
    const ActiveRunResult route = RunWith(c, PlannerKind::kRoute, seed);
    const ActiveRunResult swslam = RunWith(c, PlannerKind::kSwslam, seed);
    Print("route", route);
    Print("swslam", swslam);
    ASSERT_FALSE(swslam.centres_m.empty()) << "seed " << seed;
    // Some chosen centre was reached by the true vehicle and lies in a true dense cluster.
    int visited = 0;
    for (const Eigen::Vector2d& centre : swslam.centres_m) {
      double closest = 1e9;
      for (const StampedPose& p : swslam.run.truth) {
        closest = std::min(closest, (p.pose.translation() - centre).norm());
      }
      bool in_cluster = false;
      for (std::size_t i = 0; i + 1 < c.scenario.world.clusters.size(); ++i) {  // not background
        const ClusterParams& cluster = c.scenario.world.clusters[i];
        in_cluster = in_cluster || (centre - cluster.center_m).norm() < 2.0 * cluster.sigma_m;
      }
      visited += closest <= c.scenario.route.switch_distance_m && in_cluster ? 1 : 0;
    }
    EXPECT_GE(visited, 1) << "seed " << seed;
    EXPECT_GT(ObservationsPerLandmark(swslam), 1.2 * ObservationsPerLandmark(route))
        << "seed " << seed;
  }
}

}  // namespace
}  // namespace slamkit
