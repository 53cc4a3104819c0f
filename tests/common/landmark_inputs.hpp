#pragma once

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit::testing {

// An odometry control (forward, lateral, heading increments).
inline Control Odo(double dx, double dy, double dth) {
  Control u(3);
  u << dx, dy, dth;
  return u;
}

// A range-bearing sighting with σ = 5 cm in range and 0.01 rad in bearing.
inline PointObservation RangeBearingObs(double r, double b, LandmarkId id = kNoLandmark) {
  PointObservation obs;
  obs.z << r, b;
  obs.R = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  obs.id = id;
  return obs;
}

}  // namespace slamkit::testing
