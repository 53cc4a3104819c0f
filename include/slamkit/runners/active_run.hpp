#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/planning/swslam_planner.hpp"
#include "slamkit/runners/monte_carlo.hpp"
#include "slamkit/runners/scenario_config.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {

// What seed 001's Tables 1-3 report for one route section, counted from the simulator's truth
// (which landmark each sighting came from), so the figures do not depend on the filter's
// association.
struct SectionStats {
  RouteSection section;
  int periods = 0;                         // observation periods in the section
  int observations = 0;                    // landmark sightings in them ("total observed")
  int landmarks = 0;                       // distinct landmarks among those sightings
  double observations_per_period = 0.0;    // "average number of one-step observed landmarks"
  double observations_per_landmark = 0.0;  // "observed frequency of single landmark"
};

// A closed-loop run: the filter's RunResult (scored like RunLandmarkFilter's) and the planner's
// route sections and chosen waypoints.
struct ActiveRunResult {
  RunResult run;
  std::vector<SectionStats> sections;
  std::vector<Eigen::Vector2d> centres_m;  // the cluster centres chosen as detours, in order
  int periods = 0;                         // observation periods in the run
};

// Simulates `scenario` in `world` one step at a time and feeds each step to `filter`; after each
// observation period the planner (`planner.kind`) sees the filter's decisions on the scan and the
// filter itself, never the truth, and may send the vehicle's controller on a detour (SPEC S2).
// Noise and observation order come from `noise_rng` and `order_rng` exactly as in Simulate, so
// with PlannerKind::kRoute the result is that of RunLandmarkFilter on Simulate's run for the same
// generators; `planner_rng` seeds K-means. True ids reach the filter only with
// `known_association`.
ActiveRunResult RunActive(const ScenarioParams& scenario, const PlannerConfig& planner,
                          const LandmarkWorld& world, LandmarkSlamFilter& filter,
                          bool known_association, Rng& noise_rng, Rng& order_rng,
                          Rng& planner_rng);

// Seed 001's per-section figures from the true ids of each observation period's scan
// (period_ids[p] for period p).
SectionStats ComputeSectionStats(const RouteSection& section,
                                 const std::vector<std::vector<LandmarkId>>& period_ids);

}  // namespace slamkit
