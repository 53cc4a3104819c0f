#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/rng.hpp"

namespace slamkit {

// Landmarks uniformly distributed over an axis-aligned rectangle.
struct UniformWorldParams {
  Eigen::Vector2d min_xy_m{-5.0, -5.0};
  Eigen::Vector2d max_xy_m{25.0, 25.0};
  int count = 0;                 // used when > 0
  double density_per_m2 = 0.0;   // otherwise count = round(density × area)
  // The most landmarks a world may have: a larger count (or density × area) throws
  // std::length_error before anything is allocated. Raise it here to allow more.
  int max_landmarks = 100000;
};

// One Gaussian cluster of landmarks.
struct ClusterParams {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double sigma_m = 5.0;
  int count = 0;                 // used when > 0
  double density_per_m2 = 0.0;   // otherwise count = round(density × π (2σ)²)
};

// Where a scenario's landmarks come from.
struct WorldSpec {
  enum class Kind { kUniform, kClusters, kGiven };
  Kind kind = Kind::kUniform;
  UniformWorldParams uniform;
  std::vector<ClusterParams> clusters;
  LandmarkWorld given;            // kGiven: read by io from a CSV file
  std::uint64_t seed = 1;         // the world is the same for every Monte Carlo run
  // The most landmarks a generated world may have (all clusters together): more throws
  // std::length_error before anything is allocated. Raise it here to allow more.
  int max_landmarks = 100000;
};

LandmarkWorld GenerateUniformWorld(const UniformWorldParams& params, Rng& rng);
LandmarkWorld GenerateClusteredWorld(const std::vector<ClusterParams>& clusters, Rng& rng,
                                     int max_landmarks = 100000);
// Generates (or copies) the world a spec describes, from Rng(spec.seed).
LandmarkWorld MakeWorld(const WorldSpec& spec);

}  // namespace slamkit
