#pragma once

#include <map>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"

namespace slamkit {

// A measured motion between two poses of the path: x_from⁻¹ ⊕ x_to (odometry).
struct SmootherOdometry {
  int from = 0;
  int to = 0;
  Pose2 delta;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // of (dx [m], dy [m], dθ [rad])
};

// A point landmark seen from a pose, in the pose's frame (x forward, y left).
struct SmootherSighting {
  int pose = 0;
  LandmarkId landmark = kNoLandmark;
  Eigen::Vector2d z = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // m²
};

struct LandmarkSmootherParams {
  int max_iterations = 30;
  // Converged once no step changes the unknowns by more than tolerance × 10⁻⁶ relative to their
  // size (Ceres' parameter tolerance), or the cost no longer falls.
  double tolerance = 1e-6;
};

struct LandmarkSmootherResult {
  std::vector<Pose2> poses;
  std::map<LandmarkId, Eigen::Vector2d> landmarks;
  double chi2 = 0.0;   // sum of the squared Mahalanobis residuals at the solution
  int residuals = 0;   // scalar residuals (3 per odometry, 2 per sighting)
  int iterations = 0;
  bool converged = false;
};

// The batch maximum a posteriori of a path and its point landmarks with the associations given
// (the least squares of Dellaert and Kaess, "Square Root SAM", 2006, solved by optim's factors
// on Ceres: Levenberg-Marquardt, sparse normal Cholesky): the reference for a log without ground
// truth, against which a filter's causal estimate and final map can be compared. Pose 0 stays at
// initial_poses[0] (the gauge); landmarks start at the mean of their sightings from the initial
// poses. A local method finds the optimum near its start, so the initial path must already have
// its loops closed (an EKF with the same associations gives one; dead reckoning over a long log
// does not).
// std::invalid_argument on an index out of range, a covariance that is not positive definite, or
// a pose or landmark nothing constrains (the normal equations are then singular).
LandmarkSmootherResult SmoothLandmarkSlam(std::span<const Pose2> initial_poses,
                                          std::span<const SmootherOdometry> odometry,
                                          std::span<const SmootherSighting> sightings,
                                          const LandmarkSmootherParams& params = {});

}  // namespace slamkit
