#pragma once

#include <limits>

#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// A landmark measured as Cartesian coordinates in the robot frame (x forward, y left), as in
// the iSAM form of the Victoria Park data set: z = R(θ)ᵀ (l − t).
class RelativePointModel final : public PointSensorModel {
 public:
  explicit RelativePointModel(double max_range_m = std::numeric_limits<double>::infinity())
      : max_range_m_(max_range_m) {}

  Eigen::Vector2d Predict(const Pose2& x, const Eigen::Vector2d& l,
                          Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                          Eigen::Matrix2d* J_out_l = nullptr) const override {
    return x.TransformTo(l, J_out_x, J_out_l);
  }
  Eigen::Vector2d Invert(const Pose2& x, const Eigen::Vector2d& z,
                         Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                         Eigen::Matrix2d* J_out_z = nullptr) const override {
    return x.TransformFrom(z, J_out_x, J_out_z);
  }
  Eigen::Vector2d Innovation(const Eigen::Vector2d& z,
                             const Eigen::Vector2d& z_pred) const override {
    return z - z_pred;
  }
  double MaxRange() const override { return max_range_m_; }

 private:
  double max_range_m_;
};

}  // namespace slamkit
