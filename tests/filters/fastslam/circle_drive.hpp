// A drive once around a circle past two rings of trees, for the delayed-sampling FastSLAM tests
// (fastslam_window_test.cpp; the loop test, slow under the sanitizers, in
// fastslam_window_loop_test.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "common/landmark_inputs.hpp"
#include "common/ordered_draws.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit::testing {

// A drive once around a circle of radius 20 m past trees on two rings (radius 12 and 28 m, 24 m
// or more apart along them), sighted within 14 m; odometry and sightings with noise, ids withheld.
struct Drive {
  std::vector<Control> controls;
  std::vector<std::vector<PointObservation>> scans;  // one per pose, the first before any move
  std::vector<Eigen::Vector2d> trees;
};

inline Drive MakeDrive(int steps, std::uint64_t seed) {
  Rng rng(seed);
  Drive d;
  for (int i = 0; i < 16; ++i) {
    const double a = 2.0 * std::numbers::pi * (i + 0.5 * (i % 2)) / 16.0;
    const double r = i % 2 == 0 ? 12.0 : 28.0;
    d.trees.emplace_back(r * std::sin(a), 20.0 - r * std::cos(a));
  }
  const double turn = 2.0 * std::numbers::pi / steps;
  const Control step = Odo(2.0 * 20.0 * std::sin(0.5 * turn), 0.0, turn);
  Pose2 truth;
  for (int k = 0; k <= steps; ++k) {
    std::vector<PointObservation> scan;
    for (const Eigen::Vector2d& tree : d.trees) {
      const RangeBearing rb = PredictRangeBearing(truth, tree);
      if (rb.range_m > 14.0) continue;
      const Eigen::Vector2d e = NormalVector2(rng, 0.05, 0.01);
      scan.push_back(RangeBearingObs(rb.range_m + e.x(), WrapAngle(rb.bearing_rad + e.y())));
    }
    d.scans.push_back(scan);
    if (k == steps) break;
    truth = OdometryModel().Move(truth, step, 0.0);
    // Within the odometry model's default noise (4 cm, 0.01° a step).
    const Eigen::Vector3d e = NormalVector3(rng, 0.03, 0.03, 1.5e-4);
    d.controls.push_back(Odo(step[0] + e.x(), e.y(), step[2] + e.z()));
  }
  return d;
}

inline FastSlamParams Delayed(int particles) {
  FastSlamParams p;
  p.particles = particles;
  p.delayed_sampling = true;
  p.new_landmark_test = NewLandmarkTest::kMahalanobis;
  return p;
}

inline int LandmarksMapped(LandmarkSlamFilter& slam, const Drive& d) {
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    if (k > 0) slam.Predict(d.controls[k - 1], 0.1);
    slam.Update(d.scans[k]);
  }
  return slam.NumLandmarks();
}

}  // namespace slamkit::testing
