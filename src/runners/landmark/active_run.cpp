#include "slamkit/runners/landmark/active_run.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "slamkit/runners/landmark/landmark_run.hpp"
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

namespace {

// The route leg of PeriodState: how many route waypoints the controller has reached.
class RouteLegCounter {
 public:
  explicit RouteLegCounter(const WaypointController& controller)
      : waypoint_(controller.CurrentWaypoint()) {}
  void Update(const WaypointController& controller) {
    if (controller.CurrentWaypoint() == waypoint_) return;
    waypoint_ = controller.CurrentWaypoint();
    ++leg_;
  }
  int Leg() const { return leg_; }

 private:
  int waypoint_;
  int leg_ = 0;
};

}  // namespace

ActiveRunResult RunActive(const ScenarioParams& scenario, const PlannerConfig& planner,
                          const LandmarkWorld& world, LandmarkSlamFilter& filter,
                          bool known_association, Rng& noise_rng, Rng& order_rng,
                          Rng& planner_rng, int map_snapshots) {
  SwslamPlannerParams planner_params = planner.swslam;
  planner_params.detour = planner.kind == PlannerKind::kSwslam;
  SwslamPlanner swslam(planner_params, planner_rng);
  Simulator sim(scenario, world, noise_rng, order_rng);
  LandmarkRunRecorder recorder(filter, known_association);
  recorder.KeepMapSnapshots(map_snapshots);
  recorder.Start(scenario.initial_pose, {0.0, scenario.initial_pose}, sim.InitialObservations(),
                 sim.InitialIds());
  ActiveRunResult out;  // its period_ids are the truth, kept from the planner
  RouteLegCounter leg(sim.Controller());
  while (std::optional<SimStepWithTruth> step = sim.Step()) {
    const std::vector<AssociationDecision>& decisions =
        recorder.Step(step->inputs, scenario.dt_s, step->truth, step->ids);
    leg.Update(sim.Controller());  // every step: two waypoints may be reached between periods
    if (!step->sensor_period) continue;
    out.period_ids.push_back(std::move(step->ids));
    out.period_states.push_back({step->truth.pose.translation(), leg.Leg()});
    WaypointController& controller = sim.Controller();
    const std::optional<Eigen::Vector2d> detour = swslam.OnPeriod(
        decisions, filter, {controller.CurrentWaypoint(), controller.Detour().has_value()});
    // The planner returns its detour every period until it is reached or abandoned.
    if (detour.has_value() != controller.Detour().has_value()) controller.SetDetour(detour);
  }
  out.run = recorder.Finish(world);
  for (const RouteSection& section : swslam.Sections()) {
    out.sections.push_back(ComputeSectionStats(section, out.period_ids));
  }
  out.centres_m = swslam.ChosenCentres();
  out.periods = static_cast<int>(out.period_ids.size());
  return out;
}

std::vector<RouteSection> CarrySections(const std::vector<RouteSection>& sections,
                                        const std::vector<PeriodState>& source,
                                        const std::vector<PeriodState>& target) {
  const int periods = static_cast<int>(target.size());
  std::vector<RouteSection> carried;
  for (const RouteSection& s : sections) {
    if (s.first_period < 0 || s.first_period >= static_cast<int>(source.size())) {
      throw std::invalid_argument("CarrySections: a section starts outside its run's periods");
    }
    const PeriodState& detected = source[static_cast<std::size_t>(s.first_period)];
    const int leg = detected.route_leg;
    int start = -1;
    double nearest_m = std::numeric_limits<double>::infinity();
    for (int p = 0; p < periods; ++p) {
      if (target[p].route_leg != leg) continue;
      const double d = (target[p].true_position_m - detected.true_position_m).norm();
      if (d < nearest_m) std::tie(start, nearest_m) = std::pair(p, d);
    }
    auto after_leg = [&](int from) {
      while (from < periods && target[from].route_leg <= leg) ++from;
      return from;
    };
    RouteSection c;
    c.route_waypoint = s.route_waypoint;
    c.first_period = start >= 0 ? start : after_leg(0);
    const int end = start >= 0 ? after_leg(start) : c.first_period;
    c.end_period = end < periods || start < 0 ? end : -1;
    carried.push_back(c);
  }
  return carried;
}

}  // namespace slamkit
