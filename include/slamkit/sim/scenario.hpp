#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/models/point_sensor.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/vehicle.hpp"
#include "slamkit/sim/controller.hpp"
#include "slamkit/sim/world.hpp"

namespace slamkit {

// Everything a landmark SLAM simulation needs: world, vehicle, route and sensor (the filter's
// params come beside it: runners/scenario_config.hpp).
struct ScenarioParams {
  std::string name = "scenario";
  double dt_s = 0.025;
  int max_steps = 100000;         // stop earlier when the route is done
  WorldSpec world;
  VehicleParams vehicle;          // the true vehicle and the filter's model share it
  ControllerParams controller;
  RouteParams route;
  Pose2 initial_pose;
  RangeBearingParams sensor;
  int sensor_period_steps = 8;    // observe every this many steps
};

// One simulated time step: the true pose after it, the noisy control that led there and what the
// sensor saw from the new pose (empty between sensor periods). Observation ids are the truth.
struct SimStep {
  double t_s = 0.0;
  Pose2 true_pose;
  Control control;
  std::vector<PointObservation> observations;
};

struct SimRun {
  Pose2 initial_pose;
  // What the sensor sees before the first move: the map is anchored at the known start pose.
  std::vector<PointObservation> initial_observations;
  std::vector<SimStep> steps;
};

// Simulates one run of the scenario in `world`, drawing all noise from `rng`.
SimRun Simulate(const ScenarioParams& scenario, const LandmarkWorld& world, Rng& rng);

}  // namespace slamkit
