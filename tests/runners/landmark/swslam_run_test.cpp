// SPEC S2 / seed 001 Sec. 4.1 on configs/swslam.yaml: SWSLAM against the route alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "slamkit/runners/landmark/active_run.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

ScenarioConfig LoadSwslam() {
  return LoadScenario(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "swslam.yaml");
}

// One closed-loop EKF-SLAM run of `c` with the planner `kind`; noise, order and K-means from
// seeds `seed`, `seed` + 1000 and `seed` + 2000.
ActiveRunResult RunWith(const ScenarioConfig& c, PlannerKind kind, std::uint64_t seed) {
  PlannerConfig planner = c.planner;
  planner.kind = kind;
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  const std::unique_ptr<LandmarkSlamFilter> filter = EkfSlamFactory(c)();
  Rng noise(seed), order(seed + 1000), planner_rng(seed + 2000);
  return RunActive(c.scenario, planner, world, *filter, c.ekf.known_association(), noise, order,
                   planner_rng);
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
  const ScenarioConfig c = LoadSwslam();
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
