#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"
#include "features/polygon_room.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/features/line_extraction.hpp"
#include "slamkit/features/line_fit.hpp"

namespace slamkit {
namespace {

using testing::MakePolygonRoom;
using testing::NumericJacobian;
using testing::ScanPolygonRoom;

// Beams at `bearings` hitting `line` (the sensor at the origin), their polar coordinates perturbed
// by (ε_r, ε_φ) when `rng` is given.
std::vector<BeamPoint> PointsOnLine(const PolarLine& line, const std::vector<double>& bearings,
                                    Rng* rng = nullptr, double sigma_r = 0.0,
                                    double sigma_b = 0.0) {
  std::vector<BeamPoint> points;
  for (double phi : bearings) {
    BeamPoint b;
    b.range_m = line.rho_m / std::cos(phi - line.alpha_rad);
    b.bearing_rad = phi;
    if (rng) {
      b.range_m += rng->Normal(0.0, sigma_r);
      b.bearing_rad += rng->Normal(0.0, sigma_b);
    }
    b.p = b.range_m * Eigen::Vector2d(std::cos(b.bearing_rad), std::sin(b.bearing_rad));
    points.push_back(b);
  }
  return points;
}

std::vector<double> Bearings(double from_rad, double to_rad, int n) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(from_rad + (to_rad - from_rad) * i / (n - 1));
  return out;
}

// Eigenvalues of C_ref^{-1/2} C C_ref^{-1/2}: all 1 when C == C_ref, whatever their scales.
Eigen::Vector2d RelativeEigenvalues(const Eigen::Matrix2d& C, const Eigen::Matrix2d& C_ref) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(C, C_ref);
  return es.eigenvalues();
}

TEST(FitLineTls, ExactPointsGiveTheLineWithRhoPositiveAndAlphaWrapped) {
  for (const PolarLine truth : {PolarLine{2.0, 0.3}, PolarLine{5.0, std::numbers::pi - 1e-3},
                                PolarLine{5.0, -std::numbers::pi + 1e-3}, PolarLine{1.5, -1.2}}) {
    const auto points =
        PointsOnLine(truth, Bearings(truth.alpha_rad - 0.6, truth.alpha_rad + 0.5, 30));
    const LineFit fit = FitLineTls(points, 0.01, 0.001);
    EXPECT_NEAR(fit.line.rho_m, truth.rho_m, 1e-9);
    EXPECT_NEAR(WrapAngle(fit.line.alpha_rad - truth.alpha_rad), 0.0, 1e-9);
    EXPECT_LT(fit.residual_rms_m, 1e-9);
    for (const BeamPoint& b : points) EXPECT_NEAR(DistanceToLine(fit.line, b.p), 0.0, 1e-9);
  }
}

TEST(FitLineTls, ResidualIsTheRmsPerpendicularDistance) {
  // Pairs of points 1 cm on either side of y = 1: the fit is y = 1 and the RMS 1 cm.
  std::vector<BeamPoint> points;
  for (int i = 0; i < 20; ++i) {
    BeamPoint b;
    b.p = {0.2 * (i / 2), 1.0 + (i % 2 ? 0.01 : -0.01)};
    b.range_m = b.p.norm();
    b.bearing_rad = std::atan2(b.p.y(), b.p.x());
    points.push_back(b);
  }
  const LineFit fit = FitLineTls(points, 0.01, 0.0);
  EXPECT_NEAR(fit.line.rho_m, 1.0, 1e-9);
  EXPECT_NEAR(fit.line.alpha_rad, std::numbers::pi / 2.0, 1e-9);
  EXPECT_NEAR(fit.residual_rms_m, 0.01, 1e-9);
}

// The first-order propagation term by term: the same sum Σ J_i diag(σ_r², σ_φ²) J_iᵀ with each
// J_i = ∂(ρ, α)/∂(r_i, φ_i) taken by central differences of the fit itself.
TEST(FitLineTls, CovarianceEqualsPropagationThroughNumericJacobians) {
  const double sigma_r = 0.02, sigma_b = 0.005;
  Rng rng(4);
  for (const PolarLine truth : {PolarLine{4.0, 0.4}, PolarLine{2.5, std::numbers::pi - 0.02},
                                PolarLine{3.0, -std::numbers::pi + 0.02}}) {
    // Noisy points, so the fit is not at the noise-free optimum where some terms vanish.
    const std::vector<BeamPoint> points = PointsOnLine(
        truth, Bearings(truth.alpha_rad - 0.9, truth.alpha_rad + 0.3, 25), &rng, 0.02, 0.005);
    const LineFit fit = FitLineTls(points, sigma_r, sigma_b);
    Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      auto by_beam = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
        std::vector<BeamPoint> moved = points;
        moved[i].range_m = v[0];
        moved[i].bearing_rad = v[1];
        moved[i].p = v[0] * Eigen::Vector2d(std::cos(v[1]), std::sin(v[1]));
        const PolarLine l = FitLineTls(moved, sigma_r, sigma_b).line;
        return Eigen::Vector2d(l.rho_m, l.alpha_rad);
      };
      const Eigen::MatrixXd J =
          NumericJacobian(by_beam, Eigen::Vector2d(points[i].range_m, points[i].bearing_rad), 1);
      C += J * Eigen::Vector2d(sigma_r * sigma_r, sigma_b * sigma_b).asDiagonal() * J.transpose();
    }
    EXPECT_TRUE(fit.covariance.isApprox(C, 1e-5)) << fit.covariance << "\n" << C;
  }
}

// The propagated covariance against the sample covariance of 2000 fits of noisy beams (range and
// bearing noise both, so every term of the propagation counts).
TEST(FitLineTls, CovarianceMatchesMonteCarlo) {
  Rng rng(11);
  for (const PolarLine truth : {PolarLine{4.0, 0.4}, PolarLine{2.5, std::numbers::pi - 0.05}}) {
    const std::vector<double> bearings = Bearings(truth.alpha_rad - 0.9, truth.alpha_rad + 0.3, 40);
    const Eigen::Matrix2d C = FitLineTls(PointsOnLine(truth, bearings), 0.02, 0.005).covariance;
    constexpr int kRuns = 2000;
    Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
    for (int k = 0; k < kRuns; ++k) {
      const LineFit fit = FitLineTls(PointsOnLine(truth, bearings, &rng, 0.02, 0.005), 0.02, 0.005);
      const Eigen::Vector2d e(fit.line.rho_m - truth.rho_m,
                              WrapAngle(fit.line.alpha_rad - truth.alpha_rad));
      S += e * e.transpose();
    }
    S /= kRuns;
    const Eigen::Vector2d ev = RelativeEigenvalues(S, C);
    EXPECT_GT(ev.minCoeff(), 0.85) << "C\n" << C << "\nMonte Carlo\n" << S;
    EXPECT_LT(ev.maxCoeff(), 1.15) << "C\n" << C << "\nMonte Carlo\n" << S;
  }
}

// SPEC S1 / issue 10: extracted (ρ, α) within their stated covariance over many scans (the mean
// NEES of a consistent 2-dof estimate is 2), and the covariance close to the scatter.
TEST(LineExtraction, ExtractedLinesAreConsistentWithTheirCovarianceOverManyScans) {
  const auto room = MakePolygonRoom(0.7);
  LineExtractionParams params;
  params.sigma_range_m = 0.01;
  params.sigma_bearing_rad = 0.002;
  Rng rng(5);
  constexpr int kRuns = 2000;
  const std::size_t n_lines = room.visible_lines.size();
  std::vector<double> nees(n_lines, 0.0);
  std::vector<Eigen::Matrix2d> scatter(n_lines, Eigen::Matrix2d::Zero());
  std::vector<Eigen::Matrix2d> stated(n_lines, Eigen::Matrix2d::Zero());
  int good = 0;
  for (int k = 0; k < kRuns; ++k) {
    const auto lines = ExtractLines(ScanPolygonRoom(room, &rng, 0.01, 0.002), params);
    // Split-and-merge on noisy beams now and then leaves a wall in two pieces; such scans are
    // counted, not used.
    if (lines.size() != n_lines) continue;
    ++good;
    for (std::size_t i = 0; i < n_lines; ++i) {
      const Eigen::Vector2d e = LineInnovation(lines[i].line, room.visible_lines[i]);
      nees[i] += e.dot(lines[i].covariance.inverse() * e);
      scatter[i] += e * e.transpose();
      stated[i] += lines[i].covariance;
    }
  }
  EXPECT_GE(good, 0.99 * kRuns);
  for (std::size_t i = 0; i < n_lines; ++i) {
    nees[i] /= good;
    scatter[i] /= good;
    stated[i] /= good;
    SCOPED_TRACE(i);
    EXPECT_NEAR(nees[i], 2.0, 0.3);
    const Eigen::Vector2d ev = RelativeEigenvalues(scatter[i], stated[i]);
    EXPECT_GT(ev.minCoeff(), 0.85);
    EXPECT_LT(ev.maxCoeff(), 1.15);
  }
}

}  // namespace
}  // namespace slamkit
