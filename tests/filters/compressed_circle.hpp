#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "common/ordered_draws.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit::testing {

inline double RelativeDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

// The compressed filter's decisions for one scan against the dense filter's.
inline void ExpectSameDecisions(const std::vector<AssociationDecision>& got,
                                const std::vector<AssociationDecision>& expected, int step) {
  ASSERT_EQ(got.size(), expected.size()) << "step " << step;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].kind, expected[i].kind) << "step " << step << ", sighting " << i;
    ASSERT_EQ(got[i].landmark, expected[i].landmark) << "step " << step << ", sighting " << i;
  }
}

// A robot driving laps of a circle of `circle_m` around the origin, in steps of `step_m`, among
// landmarks on a jittered square grid of `spacing_m` out to ±`half_m`, sighting those its sensor
// sees (no ids: association is the filter's). For the compressed-update tests: two filters given
// the same controls and scans.
class CircleDrive {
 public:
  CircleDrive(double circle_m, double step_m, double spacing_m, double half_m,
              const RangeBearingParams& sensor, const OdometryParams& odometry)
      : circle_m_(circle_m), step_m_(step_m), sensor_(sensor), odometry_(odometry), rng_(32),
        truth_(circle_m, 0.0, std::numbers::pi / 2) {
    for (double x = -half_m; x <= half_m; x += spacing_m) {
      for (double y = -half_m; y <= half_m; y += spacing_m) {
        world_.push_back(Eigen::Vector2d(x, y) + UniformVector2(rng_, -0.8, 0.8, -0.8, 0.8));
      }
    }
  }

  // A filter at the true start with `update`, nearest-neighbour association and the sensor's and
  // odometry's own noise.
  EkfSlam MakeFilter(EkfUpdateMode update, EkfSlamParams params = {},
                     std::unique_ptr<SelectionPolicy> selection = {}) const {
    params.update = update;
    params.association.gate_chi2 = 9.21;
    params.association.new_landmark_chi2 = 30.0;
    params.association_margin_m = 1.0;
    EkfSlam slam(params, std::make_unique<OdometryModel>(odometry_),
                 std::make_unique<RangeBearingModel>(sensor_.params()), nullptr,
                 std::move(selection));
    slam.Reset(truth_);
    return slam;
  }

  // Moves the truth one step; returns the noisy odometry and fills `scan` with the sightings.
  Control Step(std::vector<PointObservation>& scan) {
    const Pose2 move(step_m_, 0.0, step_m_ / circle_m_);
    truth_ = truth_.Compose(move);
    Control u(3);
    u << move.x() + rng_.Normal(0, odometry_.sigma_xy_m),
        move.y() + rng_.Normal(0, odometry_.sigma_xy_m),
        move.theta() + rng_.Normal(0, odometry_.sigma_theta_rad);
    scan.clear();
    for (const Eigen::Vector2d& l : world_) {
      if (!sensor_.IsVisible(truth_, l)) continue;
      PointObservation obs;
      obs.z = sensor_.Predict(truth_, l) +
              NormalVector2(rng_, sensor_.params().sigma_range_m, sensor_.params().sigma_bearing_rad);
      obs.R = sensor_.NoiseCovariance();
      scan.push_back(obs);
    }
    return u;
  }

  const Pose2& truth() const { return truth_; }

 private:
  double circle_m_, step_m_;
  RangeBearingModel sensor_;
  OdometryParams odometry_;
  Rng rng_;
  Pose2 truth_;
  std::vector<Eigen::Vector2d> world_;
};

}  // namespace slamkit::testing
