#pragma once

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"

namespace slamkit {

// Odometry motion noise: standard deviations that grow with the distance and rotation travelled.
// The names read "s<noise in><per motion in>": srt is translation noise per radian turned, str
// rotation noise per metre driven. GMapping's ROS defaults correspond to srr 0.1, srt 0.1,
// str 0.2, stt 0.2 (its code applies its `str` to translation and `srt` to rotation); these are
// half that. The grid filter sets its own (RbpfGridSlamParams::motion; docs/grid_defaults.md).
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
