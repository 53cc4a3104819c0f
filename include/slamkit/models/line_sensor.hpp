#pragma once

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// An infinite line in Hessian normal form: the points p with p · (cos α, sin α) = ρ. ρ ≥ 0 is the
// distance from the frame's origin and α, in (−π, π], the direction of the normal pointing from
// the origin to the line. (A line through the origin has ρ = 0 and two valid α; either is kept.)
struct PolarLine {
  double rho_m = 0.0;
  double alpha_rad = 0.0;
};

// Wraps an angle to (−π, π], the range of a line's α (WrapAngle's [−π, π) with −π sent to π).
double WrapLineAngle(double angle_rad);

// The same line with ρ ≥ 0: (−ρ, α) becomes (ρ, α + π). Returns whether it flipped.
bool NormaliseLine(PolarLine* line);

// SPEC S1 (lines as landmarks): how world line `l` appears from robot pose `x`, as (ρ, α) in the
// robot frame. When the robot is on the far side of the line's normal (ρ would be negative), the
// line is flipped to ρ > 0, α + π, and the Jacobians follow the flip.
PolarLine PredictLine(const Pose2& x, const PolarLine& l,
                      Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                      Eigen::Matrix2d* J_out_l = nullptr);

// SPEC S1 (state augmentation): the world line that appears as `z` in the frame of pose `x`.
// Also brings a sensor-frame line into the robot frame when `x` is the laser's offset.
PolarLine InvertLine(const Pose2& x, const PolarLine& z,
                     Eigen::Matrix<double, 2, 3>* J_out_x = nullptr,
                     Eigen::Matrix2d* J_out_z = nullptr);

// z − ẑ as (Δρ [m], Δα [rad]) with Δα wrapped to [−π, π).
Eigen::Vector2d LineInnovation(const PolarLine& z, const PolarLine& z_pred);

// Squared Mahalanobis distance νᵀ S⁻¹ ν of the innovation ν = LineInnovation(z, z_pred), with S
// the innovation covariance (2×2, positive definite). Compare with a χ²(2) quantile.
double LineMahalanobis2(const PolarLine& z, const PolarLine& z_pred, const Eigen::Matrix2d& S);

// Length [m] by which segments [a1, b1] and [a2, b2], both projected onto the direction of a line
// with normal angle `alpha_rad`, overlap; negative: the gap between them. Two collinear walls
// far apart have the same (ρ, α) but a large negative overlap, so association needs this too.
double SegmentOverlapM(const Eigen::Vector2d& a1, const Eigen::Vector2d& b1,
                       const Eigen::Vector2d& a2, const Eigen::Vector2d& b2, double alpha_rad);

// The squared distance [m²] from point `p` to the closed segment [a, b] (a point when a = b).
double PointSegmentDistanceSq(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b);

// Whether the two segments overlap by at least `min_overlap_m` along the line (a negative value
// accepts segments with a gap of up to −min_overlap_m between them).
bool SegmentsOverlap(const Eigen::Vector2d& a1, const Eigen::Vector2d& b1,
                     const Eigen::Vector2d& a2, const Eigen::Vector2d& b2, double alpha_rad,
                     double min_overlap_m = 0.0);

}  // namespace slamkit
