// EKF-SLAM on data made up here: a robot drives a circle among six landmarks, and we give the
// filter its noisy speed readings and noisy range-bearing sightings of the landmarks.
#include <cstdio>
#include <memory>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/unicycle.hpp"

using namespace slamkit;

// ---- Filter construction: the one place to change when the EkfSlam constructor changes. ----
// A unicycle motion model (control = speed v [m/s], turn rate w [rad/s]) and a range-bearing
// sensor (measurement = range [m], bearing [rad]); nearest-neighbour data association.
EkfSlam MakeFilter(const UnicycleParams& motion, const RangeBearingParams& sensor) {
  EkfSlamParams params;  // the filter decides which landmark each sighting is (nearest neighbour)
  // A sighting farther than this (squared Mahalanobis distance) from every landmark starts a new
  // one. The default, 13.82 (chi-squared 99.9 %), lets about one in a thousand sightings of a
  // known landmark start a duplicate; in this small world we can afford a wider gate.
  params.association.new_landmark_chi2 = 25.0;
  return EkfSlam(params, std::make_unique<UnicycleModel>(motion),
                 std::make_unique<RangeBearingModel>(sensor));
}

int main() {
  // Six landmarks, two inside the circle the robot drives and four outside it.
  const std::vector<Eigen::Vector2d> landmarks = {{6, 0},   {0, 6},     {-6, 0},
                                                  {0, -6},  {1.5, 1.5}, {-1.5, -1.5}};
  const UnicycleParams motion{.sigma_v_mps = 0.05, .sigma_omega_radps = 0.01};
  const RangeBearingParams sensor{.max_range_m = 8.0, .sigma_range_m = 0.05,
                                  .sigma_bearing_rad = 0.01};
  const RangeBearingModel sensor_model(sensor);
  const UnicycleModel true_motion(motion);

  EkfSlam filter = MakeFilter(motion, sensor);
  Pose2 truth(4.0, 0.0, M_PI / 2);  // on a circle of radius 4 m around the origin, facing left
  filter.Reset(truth);              // the filter knows where it starts (zero covariance)

  Rng rng(42);  // every random number comes from here: same seed, same output
  const double dt = 0.1, v = 1.0, w = 0.25;  // 1 m/s on a 4 m radius: one lap in ~25 s
  for (int step = 0; step < 252; ++step) {
    // The true motion, and the control the filter is told: the true one plus noise.
    Control u(2);
    u << v, w;
    truth = true_motion.Move(truth, u, dt);
    Control measured(2);
    measured << v + rng.Normal(0, motion.sigma_v_mps), w + rng.Normal(0, motion.sigma_omega_radps);
    filter.Predict(measured, dt);

    // What the robot sees from its true pose: every landmark in range, with noise.
    std::vector<PointObservation> sightings;
    for (const Eigen::Vector2d& l : landmarks) {
      if (!sensor_model.IsVisible(truth, l)) continue;
      const RangeBearing z = PredictRangeBearing(truth, l);
      PointObservation obs;
      obs.z << z.range_m + rng.Normal(0, sensor.sigma_range_m),
          z.bearing_rad + rng.Normal(0, sensor.sigma_bearing_rad);
      obs.R = sensor_model.NoiseCovariance();
      sightings.push_back(obs);  // obs.id left unknown: the filter associates by itself
    }
    filter.Update(sightings);
  }

  const Pose2 est = filter.pose();
  std::printf("true pose:  x=%.3f y=%.3f theta=%.3f\n", truth.x(), truth.y(), truth.theta());
  std::printf("final pose: x=%.3f y=%.3f theta=%.3f\n", est.x(), est.y(), est.theta());
  std::printf("landmarks: %d mapped (%zu in the world)\n", filter.NumLandmarks(), landmarks.size());
  return 0;
}
