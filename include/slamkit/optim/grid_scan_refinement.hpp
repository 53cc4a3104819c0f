#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// A scan's pose refined against an occupancy grid by least squares (Hess et al. 2016, Section
// IV-C): the scan's points should land where the map, interpolated bicubically between cell
// centres, is occupied, and the pose should stay near the start. The discrete matchers stop on
// their step grid and score distances to cell centres; this one moves continuously.
struct GridRefinementParams {
  // Weights of the three kinds of residual: (1 − P) at each point, scaled by 1/√n so that the
  // balance with the two priors does not depend on how many points a scan has; and the pose's
  // move from the start, per metre and per radian (Cartographer's 2D defaults).
  double occupied_space_weight = 1.0;
  double translation_weight = 10.0;
  double rotation_weight = 40.0;
  // The occupancy given to cells never observed: low, so points are not drawn into the unknown.
  double unknown_probability = 0.1;
  int max_iterations = 20;
};

// The pose minimising Σ (w_o/√n · (1 − P(pose ⊕ p_i)))² + (w_t · Δt)² + (w_r · Δθ)², where Δ is
// the move from `start`, by Levenberg-Marquardt from `start`. `points` are in the scan's frame.
// Returns `start` for an empty scan. Throws std::invalid_argument for a negative weight or
// probability outside [0, 1].
Pose2 RefinePoseOnGrid(const OccupancyGrid& grid, const std::vector<Eigen::Vector2d>& points,
                       const Pose2& start, const GridRefinementParams& params = {});

}  // namespace slamkit
