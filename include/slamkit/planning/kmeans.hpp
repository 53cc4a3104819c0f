#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/rng.hpp"

namespace slamkit {

struct KMeansParams {
  // Number of clusters; with fewer distinct points than k there are as many clusters as
  // distinct points.
  int k = 3;
  // Assignment steps (assign each point, then move the centres) at most, at least 1; the loop
  // stops earlier as soon as an assignment step changes nothing.
  int max_iterations = 100;
};

struct KMeansResult {
  std::vector<Eigen::Vector2d> centres_m;  // one per cluster (≤ k)
  std::vector<int> assignment;             // the cluster of each point, in input order
  std::vector<int> sizes;                  // the number of points in each cluster
  int iterations = 0;                      // assignment steps run
  bool converged = false;                  // stopped because the assignment did not change
};

// K-means (MacQueen 1967; SPEC S2, seed 001 Sec. 3.1, Steps 1-4) on 2D points, seeded by
// k-means++ (Arthur & Vassilvitskii 2007) with draws from `rng`, so that one seed gives one
// clustering. A cluster that loses all its points keeps its centre. Throws
// std::invalid_argument for no points or k < 1.
KMeansResult KMeans(std::span<const Eigen::Vector2d> points_m, const KMeansParams& params,
                    Rng& rng);

// The cluster with the most points (the lowest index among equals): seed 001 Sec. 3.1, Step 5.
int LargestCluster(const KMeansResult& result);

}  // namespace slamkit
