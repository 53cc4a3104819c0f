#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/trajectory.hpp"

namespace slamkit {

// One thing one vehicle of a fleet recorded (SPEC S3): a control it applied, or a range-bearing
// sighting of a landmark or of another vehicle ("v-v"). Controls are a unicycle's (v [m/s],
// ω [rad/s]) held for dt_s from t_s: the simulator's vessels and the MRCLAM robots both drive so.
struct FleetEvent {
  enum class Kind { kControl, kLandmarkSighting, kVehicleSighting };
  Kind kind = Kind::kControl;
  double t_s = 0.0;
  int vehicle = 0;                                  // who recorded it, 0-based
  Eigen::Vector2d value = Eigen::Vector2d::Zero();  // (v, ω), or (range [m], bearing [rad])
  double dt_s = 0.0;                                // a control's duration
  LandmarkId landmark = kNoLandmark;  // a landmark sighting's id, where the source knows it
  int target = -1;                    // a vehicle sighting's vehicle, 0-based
};

// A fleet's recording: every vehicle's events in one stream ordered by time (OrderFleetEvents),
// and the start poses, known as SPEC S3 assumes. A control holds from its time until the
// vehicle's next one (dt_s later), so a consumer may move a vehicle to any sighting's time.
struct FleetLog {
  int vehicles = 0;
  std::vector<Pose2> start_poses;
  std::vector<FleetEvent> events;
};

// What a fleet's estimates are scored against: each vehicle's true path and the landmarks.
struct FleetTruth {
  std::vector<Trajectory> paths;
  LandmarkWorld world;
};

// Sorts `events` by time; at one time every sighting comes before any control (a sighting at t
// is of the poses at t, which a control at t then moves on from), then by vehicle, then in the
// order given. Stable, so a source's own order of simultaneous events is kept.
void OrderFleetEvents(std::vector<FleetEvent>& events);

}  // namespace slamkit
