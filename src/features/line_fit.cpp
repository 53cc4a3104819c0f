#include "slamkit/features/line_fit.hpp"

#include <cmath>

namespace slamkit {
namespace {

// Centroid and second moments about it of a point set.
struct Moments {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
};

Moments ComputeMoments(std::span<const BeamPoint> points) {
  Moments m;
  for (const BeamPoint& b : points) m.mean += b.p;
  m.mean /= static_cast<double>(points.size());
  for (const BeamPoint& b : points) {
    const Eigen::Vector2d d = b.p - m.mean;
    m.sxx += d.x() * d.x();
    m.syy += d.y() * d.y();
    m.sxy += d.x() * d.y();
  }
  return m;
}

// SPEC S1, line-fit covariance: C = Σ_i J_i diag(σ_r², σ_φ²) J_iᵀ, where J_i = ∂(ρ, α)/∂(r_i, φ_i)
// is the gradient of the closed-form TLS solution with respect to point i (the chain through
// ∂(x_i, y_i)/∂(r_i, φ_i)). With N = −2 S_xy and D = S_yy − S_xx, α = ½ atan2(N, D) gives
// ∂α/∂x_i = (N dx_i − D dy_i)/(N² + D²) and ∂α/∂y_i = −(D dx_i + N dy_i)/(N² + D²), where
// (dx_i, dy_i) is the point minus the centroid (the centroid's own derivative drops out because
// the deviations sum to zero); ρ = x̄ cos α + ȳ sin α adds the centroid term (cos α, sin α)/n.
Eigen::Matrix2d PropagateFitCovariance(std::span<const BeamPoint> points, const Moments& m,
                                       const PolarLine& line, double sigma_range_m,
                                       double sigma_bearing_rad) {
  const double n_pts = static_cast<double>(points.size());
  const double num = -2.0 * m.sxy, den = m.syy - m.sxx;
  const double q = num * num + den * den;
  const double c = std::cos(line.alpha_rad), s = std::sin(line.alpha_rad);
  const double lever = m.mean.y() * c - m.mean.x() * s;  // ∂ρ/∂α at fixed centroid
  const Eigen::Vector2d noise(sigma_range_m * sigma_range_m,
                              sigma_bearing_rad * sigma_bearing_rad);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const BeamPoint& b : points) {
    const Eigen::Vector2d d = b.p - m.mean;
    Eigen::Matrix2d J_line_p;  // ∂(ρ, α)/∂(x_i, y_i)
    J_line_p(1, 0) = (num * d.x() - den * d.y()) / q;
    J_line_p(1, 1) = -(den * d.x() + num * d.y()) / q;
    J_line_p(0, 0) = c / n_pts + lever * J_line_p(1, 0);
    J_line_p(0, 1) = s / n_pts + lever * J_line_p(1, 1);
    const double cb = std::cos(b.bearing_rad), sb = std::sin(b.bearing_rad);
    Eigen::Matrix2d J_p_polar;
    J_p_polar << cb, -b.range_m * sb, sb, b.range_m * cb;
    const Eigen::Matrix2d J = J_line_p * J_p_polar;
    cov += J * noise.asDiagonal() * J.transpose();
  }
  return cov;
}

}  // namespace

// SPEC S1, feature extraction (line fit): minimising Σ (x_i cos α + y_i sin α − ρ)² puts the line
// through the centroid, and about the centroid the cost is ½(S_xx + S_yy) + ½(S_xx − S_yy) cos 2α
// + S_xy sin 2α, smallest at 2α = atan2(−2 S_xy, S_yy − S_xx).
LineFit FitLineTls(std::span<const BeamPoint> points, double sigma_range_m,
                   double sigma_bearing_rad) {
  const Moments m = ComputeMoments(points);
  LineFit fit;
  const double alpha = 0.5 * std::atan2(-2.0 * m.sxy, m.syy - m.sxx);
  fit.line = {m.mean.x() * std::cos(alpha) + m.mean.y() * std::sin(alpha), alpha};
  NormaliseLine(&fit.line);
  double sum_sq = 0.0;
  for (const BeamPoint& b : points) {
    const double e = DistanceToLine(fit.line, b.p);
    sum_sq += e * e;
  }
  fit.residual_rms_m = std::sqrt(sum_sq / static_cast<double>(points.size()));
  fit.covariance =
      PropagateFitCovariance(points, m, fit.line, sigma_range_m, sigma_bearing_rad);
  return fit;
}

Eigen::Vector2d ProjectOntoLine(const PolarLine& line, const Eigen::Vector2d& p) {
  const Eigen::Vector2d n(std::cos(line.alpha_rad), std::sin(line.alpha_rad));
  return p - DistanceToLine(line, p) * n;
}

double DistanceToLine(const PolarLine& line, const Eigen::Vector2d& p) {
  return p.x() * std::cos(line.alpha_rad) + p.y() * std::sin(line.alpha_rad) - line.rho_m;
}

}  // namespace slamkit
