#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/point_sensor.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit::testing {

// A robot driving laps of a 5 m circle inside a ring of landmarks of radius 10 m, with odometry
// and range-bearing sightings drawn from the models' own noise: a run of any length whose map
// stays bounded (each landmark is seen again on every lap).
class LandmarkCircuit {
 public:
  static constexpr double kStepM = 0.1;
  static constexpr double kDriveRadiusM = 5.0;
  static constexpr double kRingRadiusM = 10.0;

  LandmarkCircuit(int landmarks, std::uint64_t seed, const OdometryParams& odometry,
                  const RangeBearingParams& sensor)
      : odometry_(odometry), sensor_(sensor), rng_(seed), truth_(kDriveRadiusM, 0.0, M_PI / 2) {
    for (int i = 0; i < landmarks; ++i) {
      const double a = 2.0 * M_PI * (i + 0.5) / landmarks;
      landmarks_.emplace_back(kRingRadiusM * std::cos(a), kRingRadiusM * std::sin(a));
    }
  }

  const Pose2& truth() const { return truth_; }
  const std::vector<Eigen::Vector2d>& landmarks() const { return landmarks_; }

  // Moves the truth one step along the circle; returns the noisy odometry increment.
  Control Step() {
    const Pose2 step(kStepM, 0.0, kStepM / kDriveRadiusM);
    truth_ = truth_.Compose(step);
    Control u(3);
    u << step.x() + rng_.Normal(0.0, odometry_.sigma_xy_m),
        step.y() + rng_.Normal(0.0, odometry_.sigma_xy_m),
        step.theta() + rng_.Normal(0.0, odometry_.sigma_theta_rad);
    return u;
  }

  // The sightings of the landmarks the sensor sees from the truth, with their ids (`out` is
  // reused so that a long run allocates nothing per step).
  void Sight(std::vector<PointObservation>& out) {
    out.clear();
    const Eigen::Matrix2d R = sensor_.NoiseCovariance();
    for (std::size_t i = 0; i < landmarks_.size(); ++i) {
      if (!sensor_.IsVisible(truth_, landmarks_[i])) continue;
      PointObservation obs;
      obs.z = sensor_.Predict(truth_, landmarks_[i]);
      obs.z += testing::NormalVector2(rng_, sensor_.params().sigma_range_m,
                                      sensor_.params().sigma_bearing_rad);
      obs.R = R;
      obs.id = static_cast<LandmarkId>(i);
      out.push_back(obs);
    }
  }

 private:
  OdometryParams odometry_;
  RangeBearingModel sensor_;
  Rng rng_;
  Pose2 truth_;
  std::vector<Eigen::Vector2d> landmarks_;
};

}  // namespace slamkit::testing
