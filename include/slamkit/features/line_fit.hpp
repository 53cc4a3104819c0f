#pragma once

#include <span>

#include <Eigen/Core>

#include "slamkit/models/line_sensor.hpp"

namespace slamkit {

// One laser return: its range and bearing as measured and the point they give, in the sensor
// frame. `beam` is the index of the beam in its scan.
struct BeamPoint {
  double range_m = 0.0;
  double bearing_rad = 0.0;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  int beam = 0;
};

// A total-least-squares line through a set of beam points.
struct LineFit {
  PolarLine line;                                            // sensor frame, ρ ≥ 0
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();      // of (ρ [m], α [rad])
  double residual_rms_m = 0.0;  // RMS of the points' perpendicular distances to the line
};

// SPEC S1, feature extraction (line fit): the line minimising the sum of squared perpendicular
// distances to `points` (at least 2), with the covariance of (ρ, α) propagated to first order from
// independent range noise σ_r [m] and bearing noise σ_φ [rad] on every beam (Arras & Siegwart
// 1997; Pfister et al. 2003).
LineFit FitLineTls(std::span<const BeamPoint> points, double sigma_range_m,
                   double sigma_bearing_rad);

// The foot of the perpendicular from `p` onto `line` (both in the same frame).
Eigen::Vector2d ProjectOntoLine(const PolarLine& line, const Eigen::Vector2d& p);

// Signed perpendicular distance [m] of `p` from `line`, positive on the side away from the origin.
double DistanceToLine(const PolarLine& line, const Eigen::Vector2d& p);

}  // namespace slamkit
