#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/features/line_extraction.hpp"
#include "slamkit/models/line_sensor.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {

// As seen from the sensor: a concave corner opens towards it (a room's corner from inside), a
// convex one points at it (a pillar's or a doorway's edge).
enum class CornerKind { kConcave, kConvex };

// A corner extracted from one scan, in the sensor frame.
struct Corner {
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // of point_m [m²]
  CornerKind kind = CornerKind::kConcave;
  double angle_rad = 0.0;  // interior angle between the two segments, in [0, π]
  int first_line = 0;      // indices into the line list it was extracted from (beam order)
  int second_line = 0;
};

// SPEC S1, feature extraction (corners): the intersection of lines `a` and `b` (same frame), with
// its Jacobian with respect to (ρ_a, α_a, ρ_b, α_b). Solves [n_a n_b]ᵀ p = (ρ_a, ρ_b); from
// A p = b, dp = A⁻¹ (db − dA p), so ∂p/∂ρ_k = A⁻¹ e_k and ∂p/∂α_k = −A⁻¹ e_k (t_k · p), with
// t_k the line's direction (−sin α_k, cos α_k). The lines must not be parallel.
Eigen::Vector2d IntersectLines(const PolarLine& a, const PolarLine& b,
                               Eigen::Matrix<double, 2, 4>* J_out_lines = nullptr);

// SPEC S1, feature extraction (corners): corners between consecutive segments of `lines` (one
// scan's, in beam order) that meet within the angle range and end-point distance of `params`.
// The covariance is J blkdiag(C_a, C_b) Jᵀ: the two fits use disjoint beams, so are independent.
std::vector<Corner> ExtractCorners(std::span<const LineSegment> lines,
                                   const LineExtractionParams& params);

// The corner as a range-bearing observation from the sensor (the point-landmark model of
// range_bearing.hpp applies to corners unchanged), with its 2×2 covariance in *R_out.
RangeBearing CornerRangeBearing(const Corner& corner, Eigen::Matrix2d* R_out = nullptr);

}  // namespace slamkit
