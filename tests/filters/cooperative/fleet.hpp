// The small fleets the cooperative filter's tests drive: two or three unicycles among point
// landmarks, their noisy controls and scans, and the filters they feed.
#pragma once

#include <memory>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/cooperative/cooperative_ekf_slam.hpp"
#include "slamkit/models/extended_observation.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/unicycle.hpp"

namespace slamkit::coop_test {

inline const UnicycleParams kMotion{0.05, 0.01};
inline const Eigen::Matrix2d kR = Eigen::Vector2d(0.1 * 0.1, 0.01 * 0.01).asDiagonal();

inline RangeBearingParams WideSensor() {
  RangeBearingParams sensor;
  sensor.max_range_m = 500.0;
  return sensor;
}

inline CooperativeEkfSlam MakeFilter(CooperativeMode mode, int vehicles, int self,
                              AssociationMethod association = AssociationMethod::kKnown,
                              JacobianEstimates jacobians = JacobianEstimates::kCurrent) {
  CooperativeEkfSlamParams p;
  p.mode = mode;
  p.ekf.association_method = association;
  p.ekf.jacobians = jacobians;
  const RangeBearingParams sensor = WideSensor();
  return CooperativeEkfSlam(p, vehicles, self, std::make_unique<UnicycleModel>(kMotion),
                            std::make_unique<RangeBearingModel>(sensor));
}

// A fleet driven and sensed with noise: the truth beside, the measurements for the filters.
struct Fleet {
  std::vector<Pose2> truth;
  std::vector<Eigen::Vector2d> landmarks;
  Rng rng{1};
  double sigma_range_m = 0.1;
  double sigma_bearing_rad = 0.01;
  Eigen::Matrix2d R() const {
    return Eigen::Vector2d(sigma_range_m * sigma_range_m, sigma_bearing_rad * sigma_bearing_rad)
        .asDiagonal();
  }

  Control Drive(int v, const Control& u, double dt) {
    truth[v] = UnicycleModel(kMotion).Move(truth[v], u, dt);
    Control noisy = u;
    noisy[0] += rng.Normal(0.0, kMotion.sigma_v_mps);
    noisy[1] += rng.Normal(0.0, kMotion.sigma_omega_radps);
    return noisy;
  }
  Eigen::Vector2d Noisy(const RangeBearing& z) {
    const double dr = rng.Normal(0.0, sigma_range_m);
    const double db = rng.Normal(0.0, sigma_bearing_rad);
    return {z.range_m + dr, WrapAngle(z.bearing_rad + db)};
  }
  // Vehicle v's scan of the landmarks `seen` (ids = their index) and of the vehicles `others`.
  FleetScan Scan(int v, std::vector<int> seen, std::vector<int> others, double t = 0.0) {
    FleetScan s;
    s.vehicle = v;
    s.t_s = t;
    for (const int l : seen) {
      s.landmarks.push_back({Noisy(PredictRangeBearing(truth[v], landmarks[l])), R(), l});
    }
    for (const int o : others) {
      s.vehicles.push_back({o, Noisy(PredictVehicleSighting(truth[v], truth[o])), R()});
    }
    return s;
  }
};

inline double PositionTrace(const CooperativeEkfSlam& f, int v) {
  return f.PoseCovarianceOf(v).topLeftCorner<2, 2>().trace();
}

}  // namespace slamkit::coop_test
