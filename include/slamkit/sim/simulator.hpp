#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/sim/controller.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {

// One simulated step as it happens: what the filter receives and, beside it, the truth.
struct SimStepWithTruth {
  SimStep inputs;
  StampedPose truth;             // the true pose after the step
  std::vector<LandmarkId> ids;   // true ids, parallel to inputs.observations
  bool sensor_period = false;    // the sensor observed at this step (its scan may be empty)
};

// The landmark-sighting simulation of a scenario one step at a time, for closed loops in which
// the route depends on the filter's estimate (SWSLAM's detours through Controller().SetDetour).
// Simulate is a loop over it, so both draw the same numbers in the same order for a seed. The
// controller steers with the true pose: the simulated vehicle reaches the points it is sent to;
// what a planner may decide from is the caller's business (the filter's estimate, never this).
// `world`, `noise_rng` and `order_rng` must outlive the simulator.
class Simulator {
 public:
  // Observes from the start pose (the scan of SimInputs::initial_observations).
  Simulator(const ScenarioParams& scenario, const LandmarkWorld& world, Rng& noise_rng,
            Rng& order_rng);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  const std::vector<PointObservation>& InitialObservations() const { return initial_obs_; }
  const std::vector<LandmarkId>& InitialIds() const { return initial_ids_; }

  // The next step toward the controller's target; nullopt once the route is done or after
  // max_steps steps.
  std::optional<SimStepWithTruth> Step();

  WaypointController& Controller() { return controller_; }
  const WaypointController& Controller() const { return controller_; }
  int StepCount() const { return k_; }

 private:
  double dt_s_;
  int max_steps_;
  int period_steps_;
  MotionKind kind_;
  std::unique_ptr<MotionModel> model_;
  RangeBearingModel sensor_;
  std::vector<const Landmark*> landmarks_;  // in id order
  Rng& noise_rng_;
  Rng& order_rng_;
  WaypointController controller_;
  Pose2 pose_;
  int k_ = 0;
  bool finished_ = false;
  std::vector<PointObservation> initial_obs_;
  std::vector<LandmarkId> initial_ids_;
};

}  // namespace slamkit
