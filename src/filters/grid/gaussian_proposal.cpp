#include "slamkit/filters/grid/gaussian_proposal.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Cholesky>

#include "slamkit/core/angle.hpp"

namespace slamkit {

ProposalDistribution GaussianProposal(const GridMapView& grid, const ScanPoints& points,
                                      const Pose2& match, const Pose2& previous,
                                      const Pose2& delta, const OdometryNoiseParams& motion,
                                      const ScanMatcherParams& matcher,
                                      const GaussianProposalParams& params) {
  constexpr int kSamples = 27;
  std::array<Eigen::Vector3d, kSamples> offsets;  // from the match, θ unwrapped
  std::array<double, kSamples> log_tau;
  int j = 0;
  for (int ix = -1; ix <= 1; ++ix) {
    for (int iy = -1; iy <= 1; ++iy) {
      for (int it = -1; it <= 1; ++it, ++j) {
        offsets[j] = {ix * params.step_xy_m, iy * params.step_xy_m, it * params.step_theta_rad};
        const Pose2 x(match.x() + offsets[j].x(), match.y() + offsets[j].y(),
                      match.theta() + offsets[j].z());
        log_tau[j] = ScanLogLikelihood(grid, points, x, matcher) +
                     OdometryMotionLogDensity(previous, delta, x, motion);
      }
    }
  }
  // Normalise in the log domain: the likelihoods of 180 beams are far below double's range.
  const double top = *std::max_element(log_tau.begin(), log_tau.end());
  double eta = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::array<double, kSamples> tau;
  for (int k = 0; k < kSamples; ++k) {
    tau[k] = std::exp(log_tau[k] - top);
    eta += tau[k];
    mean += tau[k] * offsets[k];
  }
  mean /= eta;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector3d d = offsets[k] - mean;
    covariance += tau[k] * d * d.transpose();
  }
  ProposalDistribution out;
  out.mean = Pose2(match.x() + mean.x(), match.y() + mean.y(), WrapAngle(match.theta() + mean.z()));
  out.covariance = covariance / eta;
  out.log_normaliser = top + std::log(eta / kSamples);
  return out;
}

void KeepConstrainedPart(const MatchConstraints& constraints, const Pose2& match,
                         ProposalDistribution* proposal) {
  if (constraints.unconstrained == 0) return;
  const Eigen::Matrix3d keep = constraints.KeepInWorld(match.theta());
  const Eigen::Vector3d offset =
      keep * Eigen::Vector3d(proposal->mean.x() - match.x(), proposal->mean.y() - match.y(),
                             WrapAngle(proposal->mean.theta() - match.theta()));
  proposal->mean = Pose2(match.x() + offset.x(), match.y() + offset.y(),
                         WrapAngle(match.theta() + offset.z()));
  proposal->covariance = keep * proposal->covariance * keep.transpose();
}

Pose2 SampleProposal(const ProposalDistribution& proposal, Rng& rng) {
  // A tiny jitter keeps the factor defined when every sample but one weighs nothing.
  const Eigen::Matrix3d c = proposal.covariance + 1e-12 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d L = c.llt().matrixL();
  // One draw per statement: the order in which a call's arguments are evaluated is unspecified
  // (GCC goes right to left, clang left to right), and a seed must give one output whatever the
  // compiler. Heading first, then y, then x: the order of GCC's builds, whose results docs/ holds.
  const double n_theta = rng.Normal();
  const double n_y = rng.Normal();
  const double n_x = rng.Normal();
  const Eigen::Vector3d n(n_x, n_y, n_theta);
  const Eigen::Vector3d d = L * n;
  return Pose2(proposal.mean.x() + d.x(), proposal.mean.y() + d.y(),
               WrapAngle(proposal.mean.theta() + d.z()));
}

}  // namespace slamkit
