// An MRCLAM data set as the fleet recording the cooperative filters take.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "slamkit/io/mrclam_reader.hpp"

namespace slamkit {
namespace {

struct Window {
  double begin_s;
  double end_s;  // +inf: to the end
};

std::vector<int> SelectedRobots(const MrclamDataset& data, const MrclamSelection& selection) {
  std::vector<int> robots = selection.robots;
  if (robots.empty()) {
    for (const MrclamRobot& r : data.robots) robots.push_back(r.subject);
  }
  for (std::size_t i = 0; i < robots.size(); ++i) {
    if (robots[i] < 1 || robots[i] > static_cast<int>(data.robots.size())) {
      throw InputError(fmt::format("robots: {} is not a robot of the data set (1 to {})",
                                   robots[i], data.robots.size()));
    }
    if (std::find(robots.begin(), robots.begin() + i, robots[i]) != robots.begin() + i) {
      throw InputError(fmt::format("robots: {} is listed twice", robots[i]));
    }
  }
  return robots;
}

Window WindowOf(const MrclamDataset& data, const std::vector<int>& robots,
                const MrclamSelection& selection) {
  if (!std::isfinite(selection.start_s) || selection.start_s < 0.0) {
    throw InputError(fmt::format("start: must be >= 0 s, got {}", selection.start_s));
  }
  if (selection.duration_s && !(*selection.duration_s > 0.0 && std::isfinite(*selection.duration_s))) {
    throw InputError(fmt::format("duration: must be > 0 s, got {}", *selection.duration_s));
  }
  double first = INFINITY, last = -INFINITY;
  for (const int r : robots) {
    const MrclamRobot& robot = data.robots[r - 1];
    first = std::min(first, robot.odometry.front().t_s);
    last = std::max(last, robot.odometry.back().t_s);
  }
  const Window w{first + selection.start_s,
                 selection.duration_s ? first + selection.start_s + *selection.duration_s
                                      : INFINITY};
  if (w.begin_s >= last) {
    throw InputError(fmt::format("start: {} s is after the recording's {:.1f} s of odometry",
                                 selection.start_s, last - first));
  }
  return w;
}

// Record i holds from its time until the next record's (the last one: until the window ends,
// if it has an end), clipped to the window.
void AddControls(const MrclamRobot& robot, int vehicle, const Window& w,
                 std::vector<FleetEvent>* events) {
  const auto& odo = robot.odometry;
  for (std::size_t i = 0; i < odo.size(); ++i) {
    const double until = i + 1 < odo.size() ? odo[i + 1].t_s : std::isfinite(w.end_s) ? w.end_s
                                                                                    : odo[i].t_s;
    const double from = std::max(odo[i].t_s, w.begin_s);
    const double to = std::min(until, w.end_s);
    if (to <= from) continue;
    FleetEvent e;
    e.kind = FleetEvent::Kind::kControl;
    e.t_s = from;
    e.vehicle = vehicle;
    e.value = {odo[i].v_mps, odo[i].omega_radps};
    e.dt_s = to - from;
    events->push_back(e);
  }
}

void AddSightings(const MrclamRobot& robot, int vehicle, const std::vector<int>& robots,
                  int robot_count, const Window& w, std::vector<FleetEvent>* events) {
  for (const MrclamRobot::Sighting& s : robot.sightings) {
    if (s.t_s < w.begin_s || s.t_s >= w.end_s) continue;
    FleetEvent e;
    e.t_s = s.t_s;
    e.vehicle = vehicle;
    e.value = {s.range_m, s.bearing_rad};
    if (s.subject <= robot_count) {
      const auto it = std::find(robots.begin(), robots.end(), s.subject);
      if (it == robots.end()) continue;  // a robot left out of the run
      e.kind = FleetEvent::Kind::kVehicleSighting;
      e.target = static_cast<int>(it - robots.begin());
    } else {
      e.kind = FleetEvent::Kind::kLandmarkSighting;
      e.landmark = s.subject;
    }
    events->push_back(e);
  }
}

// The latest ground-truth sample at or before `t` (the first one if all are later).
Pose2 TruthAt(const Trajectory& truth, double t) {
  const auto after = std::upper_bound(truth.begin(), truth.end(), t,
                                      [](double time, const StampedPose& p) { return time < p.t_s; });
  return after == truth.begin() ? truth.front().pose : std::prev(after)->pose;
}

}  // namespace

std::pair<FleetLog, FleetTruth> MrclamFleet(const MrclamDataset& data,
                                            const MrclamSelection& selection) {
  const std::vector<int> robots = SelectedRobots(data, selection);
  const Window w = WindowOf(data, robots, selection);
  FleetLog log;
  FleetTruth truth;
  log.vehicles = static_cast<int>(robots.size());
  for (int k = 0; k < log.vehicles; ++k) {
    const MrclamRobot& robot = data.robots[robots[k] - 1];
    log.start_poses.push_back(TruthAt(robot.truth, w.begin_s));
    AddControls(robot, k, w, &log.events);
    AddSightings(robot, k, robots, static_cast<int>(data.robots.size()), w, &log.events);
    Trajectory path;
    for (const StampedPose& p : robot.truth) {
      if (p.t_s >= w.begin_s && p.t_s <= w.end_s) path.push_back(p);
    }
    truth.paths.push_back(std::move(path));
  }
  OrderFleetEvents(log.events);
  for (const auto& [subject, position] : data.landmarks) {
    truth.world.landmarks.push_back({subject, position});
  }
  return {std::move(log), std::move(truth)};
}

}  // namespace slamkit
