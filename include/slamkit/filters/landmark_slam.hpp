#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// A named figure of what a filter's run cost (e.g. the compressed EKF's global updates), for
// the outputs; filters without such figures report none.
struct FilterCounter {
  std::string name;
  double value = 0.0;
};

// What every point-landmark SLAM filter offers (EKF-SLAM today; FastSLAM and the cooperative
// EKF next), so that one harness (Monte Carlo runs, NEES/ANEES, RMSE, association scoring, map
// error) runs on any of them without knowing how it estimates.
class LandmarkSlamFilter {
 public:
  virtual ~LandmarkSlamFilter() = default;

  // Forgets the map and starts from `pose` with covariance `pose_cov`.
  virtual void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) = 0;
  // Moves the pose with control `u` over `dt_s`; `control_noise` overrides the motion model's.
  virtual void Predict(const Control& u, double dt_s,
                       const ControlCovariance* control_noise = nullptr) = 0;
  // Takes one scan's observations; returns one decision per observation, in input order. A
  // decision's `landmark` indexes Map().landmarks and keeps naming the same landmark for the
  // filter's life, so a harness can join decisions with the truth after the run.
  virtual std::vector<AssociationDecision> Update(
      std::span<const PointObservation> observations) = 0;

  virtual Pose2 PoseEstimate() const = 0;
  virtual Eigen::Matrix3d PoseCovariance() const = 0;
  virtual int NumLandmarks() const = 0;
  // The estimated landmarks with their marginal covariances.
  virtual LandmarkMap Map() const = 0;
  // What a harness calls before it writes results: throws NumericalError (core/numerical_error)
  // if the state is not healthy (non-finite, or a covariance that is not symmetric PSD). The
  // default has nothing to check.
  virtual void CheckOutputHealth() const {}
  // Brings any deferred work up to date before outputs are read (the compressed EKF's global
  // update); reads are correct without it, only slower.
  virtual void Flush() {}
  virtual std::vector<FilterCounter> Counters() const { return {}; }
};

}  // namespace slamkit
