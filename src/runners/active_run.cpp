#include "slamkit/runners/active_run.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include "slamkit/runners/landmark_run.hpp"
#include "slamkit/sim/simulator.hpp"

namespace slamkit {

SectionStats ComputeSectionStats(const RouteSection& section,
                                 const std::vector<std::vector<LandmarkId>>& period_ids) {
  const int total = static_cast<int>(period_ids.size());
  const int end = section.end_period < 0 ? total : std::min(section.end_period, total);
  SectionStats stats;
  stats.section = section;
  std::vector<LandmarkId> seen;
  for (int p = std::max(0, section.first_period); p < end; ++p) {
    ++stats.periods;
    stats.observations += static_cast<int>(period_ids[p].size());
    seen.insert(seen.end(), period_ids[p].begin(), period_ids[p].end());
  }
  std::sort(seen.begin(), seen.end());
  stats.landmarks = static_cast<int>(std::unique(seen.begin(), seen.end()) - seen.begin());
  if (stats.periods > 0) stats.observations_per_period = double(stats.observations) / stats.periods;
  if (stats.landmarks > 0) {
    stats.observations_per_landmark = double(stats.observations) / stats.landmarks;
  }
  return stats;
}

ActiveRunResult RunActive(const ScenarioParams& scenario, const PlannerConfig& planner,
                          const LandmarkWorld& world, LandmarkSlamFilter& filter,
                          bool known_association, Rng& noise_rng, Rng& order_rng,
                          Rng& planner_rng) {
  SwslamPlannerParams planner_params = planner.swslam;
  planner_params.detour = planner.kind == PlannerKind::kSwslam;
  SwslamPlanner swslam(planner_params, planner_rng);
  Simulator sim(scenario, world, noise_rng, order_rng);
  LandmarkRunRecorder recorder(filter, known_association);
  recorder.Start(scenario.initial_pose, {0.0, scenario.initial_pose}, sim.InitialObservations(),
                 sim.InitialIds());
  std::vector<std::vector<LandmarkId>> period_ids;  // the truth, kept from the planner
  while (std::optional<SimStepWithTruth> step = sim.Step()) {
    const std::vector<AssociationDecision>& decisions =
        recorder.Step(step->inputs, scenario.dt_s, step->truth, step->ids);
    if (!step->sensor_period) continue;
    period_ids.push_back(std::move(step->ids));
    WaypointController& controller = sim.Controller();
    const std::optional<Eigen::Vector2d> detour = swslam.OnPeriod(
        decisions, filter, {controller.CurrentWaypoint(), controller.Detour().has_value()});
    // The planner returns its detour every period until it is reached or abandoned.
    if (detour.has_value() != controller.Detour().has_value()) controller.SetDetour(detour);
  }
  ActiveRunResult out;
  out.run = recorder.Finish(world);
  for (const RouteSection& section : swslam.Sections()) {
    out.sections.push_back(ComputeSectionStats(section, period_ids));
  }
  out.centres_m = swslam.ChosenCentres();
  out.periods = static_cast<int>(period_ids.size());
  return out;
}

}  // namespace slamkit
