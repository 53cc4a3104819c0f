#pragma once

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"
#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/models/odometry_sampling.hpp"

namespace slamkit {

// Where the proposal looks around the scan match: a 3 × 3 × 3 grid of poses this far apart.
// The spacing must be small against the likelihood's width (a cell shift changes a 180-beam
// scan's log-likelihood by tens), or every sample but the match weighs nothing.
struct GaussianProposalParams {
  double step_xy_m = 0.01;
  double step_theta_rad = 0.005;
};

// A Gaussian over the robot pose (x, y, θ) and the proposal's normaliser.
struct ProposalDistribution {
  Pose2 mean;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double log_normaliser = 0.0;  // log η: the particle's weight factor
};

// SPEC S4; Grisetti, Stachniss and Burgard 2007, Eqs. (15)–(19): the optimal proposal
// p(x | m, x', u, z) is approximated by a Gaussian fitted to samples x_j around the scan match,
// each weighted by τ_j = p(z | m, x_j) · p(x_j | x', u); η = Σ τ_j / K is the particle's weight
// factor. `previous` is the particle's pose at its last update and `delta` the odometry since.
ProposalDistribution GaussianProposal(const GridMapView& grid, const ScanPoints& points,
                                      const Pose2& match, const Pose2& previous,
                                      const Pose2& delta, const OdometryNoiseParams& motion,
                                      const ScanMatcherParams& matcher,
                                      const GaussianProposalParams& params = {});

// The proposal without the part that the match leaves unconstrained (MatchScan kept the guess,
// a motion sample, there): its mean moves from `match` only along the constrained directions and
// its spread lies in them, so along a featureless corridor the particles keep the motion model's
// spread instead of all climbing toward the mapped part.
void KeepConstrainedPart(const MatchConstraints& constraints, const Pose2& match,
                         ProposalDistribution* proposal);

// One draw from the proposal (its covariance's Cholesky factor times standard normals).
Pose2 SampleProposal(const ProposalDistribution& proposal, Rng& rng);

}  // namespace slamkit
