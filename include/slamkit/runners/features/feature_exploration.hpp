#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "slamkit/features/line_extraction.hpp"
#include "slamkit/filters/features/feature_ekf_slam.hpp"
#include "slamkit/filters/selection/selection_kind.hpp"
#include "slamkit/runners/features/exploration.hpp"

namespace slamkit {

struct FeatureSlamParams {
  FeatureEkfSlamParams ekf;
  LineExtractionParams extraction;
  SelectionKind selection = SelectionKind::kCovariance;
  CovarianceSelectionParams covariance;
  EntropySelectionParams entropy;
  // The odometry's noise as ExplorationParams draws it, N(0, σ²) on v and ω each control period;
  // the prediction's covariance adds it up over the periods of a step (see Step).
  double sigma_v_mps = 0.02;
  double sigma_omega_radps = 0.02;
  double control_period_s = 0.1;
  double lateral_sigma_m = 0.002;  // a floor under the lateral variance
  // The machine the modelled cost stands for (SlamTiming::kModelledCost): floating-point
  // operations per second.
  double flops_per_second = 1.0e9;
};

// The policy `params` names.
std::unique_ptr<SelectionPolicy> MakeSelectionPolicy(const FeatureSlamParams& params);

// The line-and-corner EKF-SLAM of SPEC S1 as the exploration loop's SLAM. Its modelled cost is
// the correction's counted work (CorrectionFlops).
class FeatureExplorationSlam final : public ExplorationSlam {
 public:
  FeatureExplorationSlam(const FeatureSlamParams& params, const Pose2& start);

  void Step(const Pose2& odometry_delta, const LaserScan& scan) override;
  Pose2 Estimate() const override { return slam_.pose(); }
  double ModelledCostS() const override { return modelled_cost_s_; }

  const FeatureEkfSlam& slam() const { return slam_; }
  Eigen::Matrix3d PoseCovariance() const { return slam_.PoseCovariance(); }

 private:
  FeatureSlamParams params_;
  FeatureEkfSlam slam_;
  double last_t_s_ = 0.0;
  bool started_ = false;
  double modelled_cost_s_ = 0.0;
};

}  // namespace slamkit
