#pragma once

#include <numbers>

#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

struct RangeBearingParams {
  double max_range_m = 30.0;
  double min_range_m = 0.0;
  double fov_rad = 2.0 * std::numbers::pi;  // full width, centred on the heading
  double sigma_range_m = 0.1;
  double sigma_bearing_rad = 0.0175;  // 1°
};

struct RangeBearing {
  double range_m;
  double bearing_rad;
};

// SPEC S2, Eq. 3: where landmark `l` should appear from pose `x`.
RangeBearing PredictRangeBearing(const Pose2& x, const Eigen::Vector2d& l,
                                 Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                                 Eigen::Matrix2d* J_out_l = nullptr);

// SPEC S2, Eq. 8: the landmark that produced `z`, seen from `x` (state augmentation).
Eigen::Vector2d InvertRangeBearing(const Pose2& x, const RangeBearing& z,
                                   Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                                   Eigen::Matrix2d* J_out_z = nullptr);

// Range-bearing sensor with a limited range and field of view; z = (range [m], bearing [rad]).
class RangeBearingModel final : public PointSensorModel {
 public:
  explicit RangeBearingModel(const RangeBearingParams& params = {}) : params_(params) {}

  Eigen::Vector2d Predict(const Pose2& x, const Eigen::Vector2d& l,
                          Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                          Eigen::Matrix2d* J_out_l = nullptr) const override;
  Eigen::Vector2d Invert(const Pose2& x, const Eigen::Vector2d& z,
                         Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                         Eigen::Matrix2d* J_out_z = nullptr) const override;
  Eigen::Vector2d Innovation(const Eigen::Vector2d& z,
                             const Eigen::Vector2d& z_pred) const override;
  double MaxRange() const override { return params_.max_range_m; }

  // Whether a landmark at true position `l` is inside range and field of view of pose `x`.
  bool IsVisible(const Pose2& x, const Eigen::Vector2d& l) const;
  Eigen::Matrix2d NoiseCovariance() const;
  const RangeBearingParams& params() const { return params_; }

 private:
  RangeBearingParams params_;
};

// The covariance of a Cartesian sighting `z` (x forward, y left) whose range and bearing have
// independent errors of σ_r and σ_b: J diag(σ_r², σ_b²) Jᵀ, J = ∂(x, y)/∂(r, b) from the
// range-bearing model's inverse seen from the origin (SPEC S2, Eq. 8's J_l_z).
Eigen::Matrix2d RangeBearingCovariance(const Eigen::Vector2d& z, double sigma_range_m,
                                       double sigma_bearing_rad);

}  // namespace slamkit
