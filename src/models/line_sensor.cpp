#include "slamkit/models/line_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>

namespace slamkit {

double WrapLineAngle(double angle_rad) {
  const double a = WrapAngle(angle_rad);
  return a <= -std::numbers::pi ? std::numbers::pi : a;
}

bool NormaliseLine(PolarLine* line) {
  const bool flip = line->rho_m < 0.0;
  if (flip) {
    line->rho_m = -line->rho_m;
    line->alpha_rad += std::numbers::pi;
  }
  line->alpha_rad = WrapLineAngle(line->alpha_rad);
  return flip;
}

// SPEC S1, line observation. The normal keeps its world direction, so α = α_w − θ, and the robot's
// offset along that normal, x cos α_w + y sin α_w, is taken off ρ_w.
PolarLine PredictLine(const Pose2& x, const PolarLine& l, Eigen::Matrix<double, 2, 3>* J_out_x,
                      Eigen::Matrix2d* J_out_l) {
  const double c = std::cos(l.alpha_rad), s = std::sin(l.alpha_rad);
  PolarLine z{l.rho_m - (x.x() * c + x.y() * s), l.alpha_rad - x.theta()};
  // The flip negates ρ only; α moves by the constant π, so its row keeps its sign.
  const double sign = NormaliseLine(&z) ? -1.0 : 1.0;
  if (J_out_x) *J_out_x << -sign * c, -sign * s, 0.0, 0.0, 0.0, -1.0;
  if (J_out_l) *J_out_l << sign, sign * (x.x() * s - x.y() * c), 0.0, 1.0;
  return z;
}

// SPEC S1, inverse line observation: the normal turns by θ into the world frame and the robot's
// offset along it is added back to ρ.
PolarLine InvertLine(const Pose2& x, const PolarLine& z, Eigen::Matrix<double, 2, 3>* J_out_x,
                     Eigen::Matrix2d* J_out_z) {
  const double alpha_w = z.alpha_rad + x.theta();
  const double c = std::cos(alpha_w), s = std::sin(alpha_w);
  const double d_rho_d_alpha = -x.x() * s + x.y() * c;
  PolarLine l{z.rho_m + x.x() * c + x.y() * s, alpha_w};
  const double sign = NormaliseLine(&l) ? -1.0 : 1.0;
  if (J_out_x) *J_out_x << sign * c, sign * s, sign * d_rho_d_alpha, 0.0, 0.0, 1.0;
  if (J_out_z) *J_out_z << sign, sign * d_rho_d_alpha, 0.0, 1.0;
  return l;
}

Eigen::Vector2d LineInnovation(const PolarLine& z, const PolarLine& z_pred) {
  return {z.rho_m - z_pred.rho_m, WrapAngle(z.alpha_rad - z_pred.alpha_rad)};
}

double LineMahalanobis2(const PolarLine& z, const PolarLine& z_pred, const Eigen::Matrix2d& S) {
  const Eigen::Vector2d nu = LineInnovation(z, z_pred);
  return nu.dot(S.ldlt().solve(nu));
}

// Both segments are reduced to intervals of the coordinate along the line's direction
// (−sin α, cos α); their overlap is the shorter interval end minus the later interval start.
double SegmentOverlapM(const Eigen::Vector2d& a1, const Eigen::Vector2d& b1,
                       const Eigen::Vector2d& a2, const Eigen::Vector2d& b2, double alpha_rad) {
  const Eigen::Vector2d t(-std::sin(alpha_rad), std::cos(alpha_rad));
  const double u1 = t.dot(a1), v1 = t.dot(b1), u2 = t.dot(a2), v2 = t.dot(b2);
  const double lo = std::max(std::min(u1, v1), std::min(u2, v2));
  const double hi = std::min(std::max(u1, v1), std::max(u2, v2));
  return hi - lo;
}

double PointSegmentDistanceSq(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length_sq = ab.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).squaredNorm();
}

bool SegmentsOverlap(const Eigen::Vector2d& a1, const Eigen::Vector2d& b1,
                     const Eigen::Vector2d& a2, const Eigen::Vector2d& b2, double alpha_rad,
                     double min_overlap_m) {
  return SegmentOverlapM(a1, b1, a2, b2, alpha_rad) >= min_overlap_m;
}

}  // namespace slamkit
