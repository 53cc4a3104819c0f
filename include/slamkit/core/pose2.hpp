#pragma once

#include <Eigen/Core>

#include "slamkit/core/angle.hpp"

namespace slamkit {

// A rigid motion in the plane, SE(2): position (x, y) in metres and heading theta in radians,
// kept wrapped to [-pi, pi). As a transform it maps points from the body frame to the parent frame.
// Jacobians are with respect to the (x, y, theta) coordinates of the arguments.
class Pose2 {
 public:
  Pose2() = default;
  Pose2(double x_m, double y_m, double theta_rad) : x_(x_m), y_(y_m), theta_(WrapAngle(theta_rad)) {}
  explicit Pose2(const Eigen::Vector3d& v) : Pose2(v.x(), v.y(), v.z()) {}

  double x() const { return x_; }
  double y() const { return y_; }
  double theta() const { return theta_; }
  Eigen::Vector2d translation() const { return {x_, y_}; }
  Eigen::Vector3d vector() const { return {x_, y_, theta_}; }
  Eigen::Matrix2d rotation() const;

  // this ⊕ other: `other` expressed in this frame, brought to the parent frame.
  Pose2 Compose(const Pose2& other, Eigen::Matrix3d* J_out_this = nullptr,
                Eigen::Matrix3d* J_out_other = nullptr) const;
  Pose2 Inverse(Eigen::Matrix3d* J_out_this = nullptr) const;
  // this⁻¹ ⊕ other: `other` seen from this frame.
  Pose2 Between(const Pose2& other, Eigen::Matrix3d* J_out_this = nullptr,
                Eigen::Matrix3d* J_out_other = nullptr) const;

  // Body-frame point p to the parent frame.
  Eigen::Vector2d TransformFrom(const Eigen::Vector2d& p,
                                Eigen::Matrix<double, 2, 3>* J_out_this = nullptr,
                                Eigen::Matrix2d* J_out_p = nullptr) const;
  // Parent-frame point p to the body frame.
  Eigen::Vector2d TransformTo(const Eigen::Vector2d& p,
                              Eigen::Matrix<double, 2, 3>* J_out_this = nullptr,
                              Eigen::Matrix2d* J_out_p = nullptr) const;

 private:
  double x_ = 0.0;
  double y_ = 0.0;
  double theta_ = 0.0;
};

// Error vector a ⊖ b in coordinates: (dx, dy, wrapped dtheta), as used by NEES and RMSE.
Eigen::Vector3d PoseError(const Pose2& estimate, const Pose2& truth);

}  // namespace slamkit
