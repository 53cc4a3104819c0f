#include "slamkit/runners/features/feature_exploration.hpp"

#include <algorithm>
#include <cmath>

#include "slamkit/features/scan_features.hpp"
#include "slamkit/models/odometry.hpp"

namespace slamkit {

std::unique_ptr<SelectionPolicy> MakeSelectionPolicy(const FeatureSlamParams& params) {
  return MakeSelectionPolicy(params.selection, params.covariance, params.entropy);
}

FeatureExplorationSlam::FeatureExplorationSlam(const FeatureSlamParams& params,
                                               const Pose2& start)
    : params_(params),
      slam_(params.ekf, std::make_unique<OdometryModel>(), MakeSelectionPolicy(params)) {
  slam_.Reset(start);
}

// The odometry increment as the control of an OdometryModel, with the covariance that the
// exploration's per-period noise adds up to over the step (n periods of Δt: n (σ Δt)² on the
// distance and on the heading; the lateral part from the heading noise over half the distance).
void FeatureExplorationSlam::Step(const Pose2& odometry_delta, const LaserScan& scan) {
  if (started_) {
    const double periods = std::max(scan.t_s - last_t_s_, 0.0) / params_.control_period_s;
    const double var_v = periods * std::pow(params_.sigma_v_mps * params_.control_period_s, 2);
    const double var_theta =
        periods * std::pow(params_.sigma_omega_radps * params_.control_period_s, 2);
    Control u(3);
    u << odometry_delta.x(), odometry_delta.y(), odometry_delta.theta();
    ControlCovariance Q = ControlCovariance::Zero(3, 3);
    Q(0, 0) = var_v + 1e-12;
    Q(1, 1) = std::pow(0.5 * odometry_delta.translation().norm(), 2) * var_theta +
              std::pow(params_.lateral_sigma_m, 2);
    Q(2, 2) = var_theta + 1e-12;
    slam_.Predict(u, 0.0, &Q);
  }
  started_ = true;
  last_t_s_ = scan.t_s;
  slam_.Update(ToRobotFrame(ExtractFeatures(scan, params_.extraction), scan.laser_offset));
  modelled_cost_s_ =
      CorrectionFlops(params_.selection, slam_.LastSelectionStats(), slam_.ekf().StateSize()) /
      params_.flops_per_second;
}

}  // namespace slamkit
