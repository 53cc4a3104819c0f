#pragma once

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"

namespace slamkit {

// Odometry motion noise: standard deviations that grow with the distance and rotation travelled.
// The names read "s<noise in><per motion in>": srt is translation noise per radian turned, str
// rotation noise per metre driven. GMapping's ROS defaults correspond to srr 0.1, srt 0.1,
// str 0.2, stt 0.2 (its code applies its `str` to translation and `srt` to rotation); ours are
// half that: on intel.clf with 30 particles GMapping's values sent one seed in three off the map
// (3.9 m relation error) and these gave 0.042-0.046 m on seeds 1-3 (before tracking).
// Checked on two logs with today's grid RBPF (seed 1, 30 particles, all four values equal):
//   value   Intel relations (trans, rot)        CSAIL (suite/csail.log.gz vs its reference)
//   0.025   0.0249 ± 0.0230 m, 0.480 ± 0.530°   ATE 1.454 m rms (5.68 max), RPE 0.062 m, 1.69°
//   0.05    0.0273 ± 0.0226 m, 0.545 ± 0.593°   ATE 0.253 m rms (0.55 max), RPE 0.064 m, 1.35°
//   0.1     0.0300 ± 0.0349 m, 0.544 ± 0.638°   ATE 0.119 m rms (0.50 max), RPE 0.064 m, 1.45°
// The logs disagree on both sides (0.025 loses CSAIL, 0.1 is worse on Intel and in CSAIL's
// rotation RPE), so 0.05 stays.
struct OdometryNoiseParams {
  double srr = 0.05;  // m per m
  double srt = 0.05;  // m per rad
  double str = 0.05;  // rad per m
  double stt = 0.05;  // rad per rad
};

// Standard deviations (x, y, θ) of the noise on the increment `delta`, as SampleOdometryMotion
// draws it.
Eigen::Vector3d OdometryNoiseSigmas(const Pose2& delta, const OdometryNoiseParams& noise);

// Log-density, up to a constant, that odometry `delta` from `from` ends at `to` (the increment's
// noise components as independent Gaussians; each σ floored at 1 mm or 1 mrad, so a robot that
// did not move still has a proper density).
double OdometryMotionLogDensity(const Pose2& from, const Pose2& delta, const Pose2& to,
                                const OdometryNoiseParams& noise);

// Draws the pose reached from `pose` after the odometry increment `delta` (robot frame), with
// each component of the increment perturbed by zero-mean Gaussian noise scaled as above.
Pose2 SampleOdometryMotion(const Pose2& pose, const Pose2& delta, const OdometryNoiseParams& noise,
                           Rng& rng);

}  // namespace slamkit
