#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "slamkit/core/fleet_log.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/unicycle.hpp"
#include "slamkit/sim/controller.hpp"
#include "slamkit/sim/world.hpp"

namespace slamkit {

// One vehicle of a simulated fleet: where it starts and the closed route it drives.
struct FleetVehicleSpec {
  Pose2 start;
  RouteParams route;
};

// SPEC S3's simulation: several unicycle vehicles in one world of point landmarks, each driving
// its route, sensing the landmarks and the other vehicles with range-bearing sensors.
struct FleetScenarioParams {
  std::string name = "fleet";
  double dt_s = 1.0;
  int max_steps = 100000;  // stop earlier when every route is done
  WorldSpec world;
  std::vector<FleetVehicleSpec> vehicles;
  UnicycleParams motion;  // the control noise (each vehicle's own draws)
  ControllerParams controller;
  RangeBearingParams sensor;          // landmark sightings
  RangeBearingParams vehicle_sensor;  // v-v sightings
  int sensor_period_steps = 1;
};

struct FleetRun {
  FleetLog log;
  FleetTruth truth;
  // The true landmark of each event, parallel to log.events (kNoLandmark for the others): the
  // log's sightings carry none, so that a filter learns ids only when a caller copies them.
  std::vector<LandmarkId> landmark_ids;
};

// Simulates the fleet: vehicle v's control and sensor noise from vehicle_noise[v] (one stream
// per vehicle, so that one vehicle's draws never depend on another's). At each step every
// vehicle's noisy control (held for dt_s), then after the move, on sensor periods, its sightings
// of the landmarks (in id order) and of the vehicles (in index order) within range; sightings
// are also taken from the start poses. A vehicle whose route is done stops, and records nothing
// more. Throws std::invalid_argument for no vehicle or not one stream per vehicle.
FleetRun SimulateFleet(const FleetScenarioParams& params, const LandmarkWorld& world,
                       std::span<Rng> vehicle_noise);

// Copies the true landmark ids into the log's sightings (known association; only then).
void CopyTrueIds(const FleetRun& run, FleetLog& log);

// What a fleet shares (SPEC S3): every vehicle sends its controls and its raw sightings.
struct MessageParams {
  double loss_probability = 0.0;  // each sighting message (a vehicle's sightings at one time)
  int max_sightings = 0;          // per message, the nearest kept (a bandwidth cap; 0: none)
  // Every message (controls and sightings) arrives at most this long after it was sent: the
  // link's worst latency. A receiver then runs its filter this far behind (coop_run.hpp).
  double delay_s = 0.0;
};

// Which events of `log` reach vehicle `receiver`: all its own, every other vehicle's controls
// (small, resent until acknowledged), and the other vehicles' sighting messages that survive
// loss (drawn from `rng`, message by message in log order) and the cap. Indices into log.events,
// in order.
std::vector<int> DeliveredEvents(const FleetLog& log, int receiver, const MessageParams& params,
                                 Rng& rng);

}  // namespace slamkit
