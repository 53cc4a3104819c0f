// SPEC S3: a fleet of vehicles in one landmark world, and what they share.
#include "slamkit/sim/fleet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "slamkit/core/angle.hpp"
#include "slamkit/models/extended_observation.hpp"

namespace slamkit {
namespace {

struct VehicleState {
  Pose2 pose;
  WaypointController controller;
  bool done = false;
};

FleetEvent Sighting(double t, int v, const RangeBearing& z, const RangeBearingParams& sensor,
                    Rng& rng) {
  FleetEvent e;
  e.t_s = t;
  e.vehicle = v;
  const double range = z.range_m + rng.Normal(0.0, sensor.sigma_range_m);
  e.value = {range, WrapAngle(z.bearing_rad + rng.Normal(0.0, sensor.sigma_bearing_rad))};
  return e;
}

bool Visible(const RangeBearingParams& sensor, const RangeBearing& z) {
  return z.range_m <= sensor.max_range_m && z.range_m >= sensor.min_range_m &&
         std::abs(z.bearing_rad) <= 0.5 * sensor.fov_rad;
}

// Vehicle v's sightings at time t from its true pose: landmarks in id order, then vehicles.
void Sense(const FleetScenarioParams& p, const std::vector<const Landmark*>& landmarks,
           const std::vector<VehicleState>& fleet, int v, double t, Rng& rng, FleetRun* run) {
  for (const Landmark* l : landmarks) {
    const RangeBearing z = PredictRangeBearing(fleet[v].pose, l->position_m);
    if (!Visible(p.sensor, z)) continue;
    FleetEvent e = Sighting(t, v, z, p.sensor, rng);
    e.kind = FleetEvent::Kind::kLandmarkSighting;
    run->log.events.push_back(e);
    run->landmark_ids.push_back(l->id);
  }
  for (int o = 0; o < static_cast<int>(fleet.size()); ++o) {
    if (o == v) continue;
    const RangeBearing z = PredictVehicleSighting(fleet[v].pose, fleet[o].pose);
    if (!Visible(p.vehicle_sensor, z)) continue;
    FleetEvent e = Sighting(t, v, z, p.vehicle_sensor, rng);
    e.kind = FleetEvent::Kind::kVehicleSighting;
    e.target = o;
    run->log.events.push_back(e);
    run->landmark_ids.push_back(kNoLandmark);
  }
}

}  // namespace

FleetRun SimulateFleet(const FleetScenarioParams& p, const LandmarkWorld& world,
                       std::span<Rng> vehicle_noise) {
  const int n = static_cast<int>(p.vehicles.size());
  if (n == 0 || static_cast<int>(vehicle_noise.size()) != n) {
    throw std::invalid_argument("SimulateFleet: needs vehicles, each with its noise stream");
  }
  std::vector<const Landmark*> landmarks;
  for (const Landmark& l : world.landmarks) landmarks.push_back(&l);
  std::sort(landmarks.begin(), landmarks.end(),
            [](const Landmark* a, const Landmark* b) { return a->id < b->id; });
  FleetRun run;
  run.log.vehicles = n;
  run.truth.world = world;
  run.truth.paths.resize(n);
  std::vector<VehicleState> fleet;
  for (int v = 0; v < n; ++v) {
    fleet.push_back({p.vehicles[v].start,
                     WaypointController(p.vehicles[v].route, p.controller, MotionKind::kUnicycle)});
    run.log.start_poses.push_back(p.vehicles[v].start);
    run.truth.paths[v].push_back({0.0, p.vehicles[v].start});
  }
  for (int v = 0; v < n; ++v) Sense(p, landmarks, fleet, v, 0.0, vehicle_noise[v], &run);
  const UnicycleModel model(p.motion);
  const int period = std::max(1, p.sensor_period_steps);
  for (int k = 0; k < p.max_steps; ++k) {
    const double t = k * p.dt_s;
    for (int v = 0; v < n; ++v) {
      VehicleState& s = fleet[v];
      if (s.done) continue;
      const Control command = s.controller.Command(s.pose, p.dt_s);
      s.done = s.controller.Done();
      if (s.done) continue;
      s.pose = model.Move(s.pose, command, p.dt_s);
      FleetEvent e;
      e.kind = FleetEvent::Kind::kControl;
      e.t_s = t;
      e.vehicle = v;
      e.dt_s = p.dt_s;
      const double dv = vehicle_noise[v].Normal(0.0, p.motion.sigma_v_mps);
      e.value = {command[0] + dv, command[1] + vehicle_noise[v].Normal(0.0, p.motion.sigma_omega_radps)};
      run.log.events.push_back(e);
      run.landmark_ids.push_back(kNoLandmark);
      run.truth.paths[v].push_back({t + p.dt_s, s.pose});
    }
    if (std::all_of(fleet.begin(), fleet.end(), [](const VehicleState& s) { return s.done; })) break;
    if ((k + 1) % period != 0) continue;
    for (int v = 0; v < n; ++v) {
      if (!fleet[v].done) Sense(p, landmarks, fleet, v, t + p.dt_s, vehicle_noise[v], &run);
    }
  }
  return run;
}

void CopyTrueIds(const FleetRun& run, FleetLog& log) {
  for (std::size_t i = 0; i < log.events.size(); ++i) log.events[i].landmark = run.landmark_ids[i];
}

}  // namespace slamkit
