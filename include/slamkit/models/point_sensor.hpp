#pragma once

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"

namespace slamkit {

// One sighting of a point landmark: the measurement, its noise covariance and, where the source
// knows it (a simulator's truth or a data set's association), the landmark it came from.
struct PointObservation {
  Eigen::Vector2d z = Eigen::Vector2d::Zero();
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  LandmarkId id = kNoLandmark;
};

// A sensor that measures a point landmark l from pose x as a 2-vector z = h(x, l), invertible so
// that a new landmark can be initialised from its first sighting (state augmentation).
class PointSensorModel {
 public:
  virtual ~PointSensorModel() = default;

  virtual Eigen::Vector2d Predict(const Pose2& x, const Eigen::Vector2d& l,
                                  Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                                  Eigen::Matrix2d* J_out_l = nullptr) const = 0;
  virtual Eigen::Vector2d Invert(const Pose2& x, const Eigen::Vector2d& z,
                                 Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                                 Eigen::Matrix2d* J_out_z = nullptr) const = 0;
  // z − ẑ, with any angular component wrapped.
  virtual Eigen::Vector2d Innovation(const Eigen::Vector2d& z,
                                     const Eigen::Vector2d& z_pred) const = 0;
  // Largest distance at which a landmark can be seen; lets association skip far landmarks.
  virtual double MaxRange() const = 0;
};

}  // namespace slamkit
