#pragma once

#include <span>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/trajectory.hpp"

namespace slamkit {

struct HeadingDriftParams {
  // Consecutive steps per window; the windows do not overlap (a last, shorter one is left out).
  int window_steps = 100;
};

// How a vehicle's odometry turns against an estimate of its path. A wheel odometry whose
// steering or wheel-radius calibration is off turns by a bias proportional to the distance
// driven; filter noise that grows with the square root of the distance covers such a bias badly
// (a particle cloud drawn from it misses the true heading after a long stretch).
struct HeadingDriftFit {
  // b in: the estimate's turn over a window = the odometry's + b × the distance driven (least
  // squares over the windows). Adding b × |step| to each step's turn removes the bias.
  double drift_rad_per_m = 0.0;
  double rms_before_rad = 0.0;  // windows' turn disagreement (estimate − odometry)
  double rms_after_rad = 0.0;   // what is left of it after b × distance
  int windows = 0;
};

// `odometry[k]` is the increment from estimate[k] to estimate[k + 1]; the estimate's turn is
// summed step by step (so windows may turn by more than π). std::invalid_argument if the sizes
// do not match, the window is < 1 step, or there is no whole window.
HeadingDriftFit FitHeadingDrift(std::span<const Pose2> odometry, const Trajectory& estimate,
                                const HeadingDriftParams& params = {});

}  // namespace slamkit
