#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/planning/swslam_planner.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"
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

// Where the true vehicle was at one observation period, and on which leg of its route: leg j
// runs from reaching the route's j-th waypoint (counted over all loops; the start heads for
// waypoint 0, leg 0) to reaching the next. A detour does not change the leg (waypoints passed on
// a detour do not count), so leg j of a route run and of a SWSLAM run end at the same waypoint.
struct PeriodState {
  Eigen::Vector2d true_position_m = Eigen::Vector2d::Zero();
  int route_leg = 0;
};

// A closed-loop run: the filter's RunResult (scored like RunLandmarkFilter's) and the planner's
// route sections and chosen waypoints, with what section statistics are computed from.
struct ActiveRunResult {
  RunResult run;
  std::vector<SectionStats> sections;
  std::vector<Eigen::Vector2d> centres_m;  // the cluster centres chosen as detours, in order
  int periods = 0;                         // observation periods in the run
  std::vector<std::vector<LandmarkId>> period_ids;  // each period's true sightings
  std::vector<PeriodState> period_states;           // one per period
};

// Simulates `scenario` in `world` one step at a time and feeds each step to `filter`; after each
// observation period the planner (`planner.kind`) sees the filter's decisions on the scan and the
// filter itself, never the truth, and may send the vehicle's controller on a detour (SPEC S2).
// Noise and observation order come from `noise_rng` and `order_rng` exactly as in Simulate, so
// with PlannerKind::kRoute the result is that of RunLandmarkFilter on Simulate's run for the same
// generators; `planner_rng` seeds K-means. True ids reach the filter only with
// `known_association`. `map_snapshots` > 0 keeps a map history (RunLandmarkFilter's).
ActiveRunResult RunActive(const ScenarioParams& scenario, const PlannerConfig& planner,
                          const LandmarkWorld& world, LandmarkSlamFilter& filter,
                          bool known_association, Rng& noise_rng, Rng& order_rng,
                          Rng& planner_rng, int map_snapshots = 0);

// Seed 001's per-section figures from the true ids of each observation period's scan
// (period_ids[p] for period p).
SectionStats ComputeSectionStats(const RouteSection& section,
                                 const std::vector<std::vector<LandmarkId>>& period_ids);

// The sections of another run of the same route carried onto this one: seed 001 compares the
// same sections across methods ("from the observed area of interest to the next waypoint"), so a
// route run is measured on the sections a SWSLAM run with the same seed detected. Section s of
// `source` starts, in `target`, at the period of the same route leg nearest to where the source
// vehicle was when it detected the area (the first such period on a tie), and ends when the
// target leaves that leg, i.e. reaches the same route waypoint (-1: it never does). A leg the
// target never drove gives an empty section (no periods) at the target's first later period.
std::vector<RouteSection> CarrySections(const std::vector<RouteSection>& sections,
                                        const std::vector<PeriodState>& source,
                                        const std::vector<PeriodState>& target);

}  // namespace slamkit
