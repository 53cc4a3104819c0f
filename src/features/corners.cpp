#include "slamkit/features/corners.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace slamkit {
namespace {

// Interior angle at `corner` between the segments' far ends, in [0, π].
double InteriorAngle(const Eigen::Vector2d& corner, const LineSegment& a, const LineSegment& b) {
  const Eigen::Vector2d u = a.start_m - corner, v = b.end_m - corner;
  const double c = u.dot(v) / (u.norm() * v.norm());
  return std::acos(std::clamp(c, -1.0, 1.0));
}

// SPEC S1, corner labels. ρ ≥ 0 puts each line's normal pointing away from the sensor, so at a
// concave corner the other wall lies on the sensor's side of this one (negative distance) and at
// a convex corner beyond it. Both walls are asked, so a short wall does not decide alone.
CornerKind Classify(const LineSegment& a, const LineSegment& b) {
  const double side = DistanceToLine(a.line, 0.5 * (b.start_m + b.end_m)) +
                      DistanceToLine(b.line, 0.5 * (a.start_m + a.end_m));
  return side < 0.0 ? CornerKind::kConcave : CornerKind::kConvex;
}

}  // namespace

// SPEC S1, feature extraction (corners): line intersection and its Jacobian.
Eigen::Vector2d IntersectLines(const PolarLine& a, const PolarLine& b,
                               Eigen::Matrix<double, 2, 4>* J_out_lines) {
  Eigen::Matrix2d A;
  A << std::cos(a.alpha_rad), std::sin(a.alpha_rad), std::cos(b.alpha_rad), std::sin(b.alpha_rad);
  const Eigen::Matrix2d A_inv = A.inverse();
  const Eigen::Vector2d p = A_inv * Eigen::Vector2d(a.rho_m, b.rho_m);
  if (J_out_lines) {
    const double ta = -std::sin(a.alpha_rad) * p.x() + std::cos(a.alpha_rad) * p.y();
    const double tb = -std::sin(b.alpha_rad) * p.x() + std::cos(b.alpha_rad) * p.y();
    Eigen::Matrix<double, 2, 4> dB;  // ∂(b − A p)/∂(ρ_a, α_a, ρ_b, α_b) at fixed p
    dB << 1.0, -ta, 0.0, 0.0, 0.0, 0.0, 1.0, -tb;
    *J_out_lines = A_inv * dB;
  }
  return p;
}

// SPEC S1, feature extraction (corners).
std::vector<Corner> ExtractCorners(std::span<const LineSegment> lines,
                                   const LineExtractionParams& params) {
  std::vector<Corner> corners;
  for (int i = 0; i + 1 < static_cast<int>(lines.size()); ++i) {
    const LineSegment& a = lines[i];
    const LineSegment& b = lines[i + 1];
    // Nearly parallel lines meet far away or nowhere; the angle test would reject them anyway,
    // but only after an ill-conditioned solve.
    if (std::abs(std::sin(b.line.alpha_rad - a.line.alpha_rad)) < 1e-6) continue;
    Eigen::Matrix<double, 2, 4> J;
    Corner c;
    c.point_m = IntersectLines(a.line, b.line, &J);
    if ((a.end_m - c.point_m).norm() > params.max_corner_endpoint_distance_m ||
        (b.start_m - c.point_m).norm() > params.max_corner_endpoint_distance_m) {
      continue;
    }
    c.angle_rad = InteriorAngle(c.point_m, a, b);
    if (c.angle_rad < params.min_corner_angle_rad || c.angle_rad > params.max_corner_angle_rad) {
      continue;
    }
    Eigen::Matrix4d C_lines = Eigen::Matrix4d::Zero();
    C_lines.topLeftCorner<2, 2>() = a.covariance;
    C_lines.bottomRightCorner<2, 2>() = b.covariance;
    c.covariance = J * C_lines * J.transpose();
    c.kind = Classify(a, b);
    c.first_line = i;
    c.second_line = i + 1;
    corners.push_back(c);
  }
  return corners;
}

RangeBearing CornerRangeBearing(const Corner& corner, Eigen::Matrix2d* R_out) {
  Eigen::Matrix2d J;
  const RangeBearing z = PredictRangeBearing(Pose2(), corner.point_m, nullptr, &J);
  if (R_out) *R_out = J * corner.covariance * J.transpose();
  return z;
}

}  // namespace slamkit
