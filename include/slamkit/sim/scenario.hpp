#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/core/trajectory.hpp"
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

// What the filter receives at one time step: the noisy control that led to it and what the
// sensor saw from the new pose (empty between sensor periods). The observations carry no
// landmark ids (`id` is kNoLandmark) and come in no particular order; their true ids are in
// SimTruth, beside.
struct SimStep {
  double t_s = 0.0;
  Control control;
  std::vector<PointObservation> observations;
};

// The filter's inputs for one run.
struct SimInputs {
  Pose2 initial_pose;
  // What the sensor sees before the first move: the map is anchored at the known start pose.
  std::vector<PointObservation> initial_observations;
  std::vector<SimStep> steps;
};

// The truth of one run, beside the inputs and parallel to them.
struct SimTruth {
  // The true pose at the start (t = 0) and after each step: poses[k + 1] goes with steps[k].
  Trajectory poses;
  // The true landmark id of each observation, in the inputs' order:
  // initial_ids[i] ↔ initial_observations[i], ids[k][i] ↔ steps[k].observations[i].
  std::vector<LandmarkId> initial_ids;
  std::vector<std::vector<LandmarkId>> ids;
};

struct SimRun {
  SimInputs inputs;
  SimTruth truth;
};

// Copies the true ids into the observations: what a caller does for known association, and only
// then (the filter never sees the truth otherwise).
void CopyTrueIds(const SimTruth& truth, SimInputs& inputs);

// Simulates one run of the scenario in `world`, drawing all noise from `noise_rng` and the order
// of the observations within each scan (a random permutation, independent of the landmark ids)
// from `order_rng`, so that the noise draws do not depend on the shuffling.
SimRun Simulate(const ScenarioParams& scenario, const LandmarkWorld& world, Rng& noise_rng,
                Rng& order_rng);

}  // namespace slamkit
