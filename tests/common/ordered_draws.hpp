#pragma once

#include <Eigen/Core>

#include "slamkit/core/rng.hpp"

// Vectors of random draws, drawn in one fixed order. The arguments of a call are evaluated in an
// unspecified order (GCC goes from the last to the first, clang from the first to the last), so
// `Eigen::Vector2d(rng.Normal(), rng.Normal())` holds other numbers under each compiler and a
// seeded test would test other data. These draw the last component first, as the GCC builds did
// when the tests' seeds and bounds were chosen: GCC's data is unchanged and clang's equals it.
namespace slamkit::testing {

inline Eigen::Vector2d UniformVector2(Rng& rng, double lo0, double hi0, double lo1, double hi1) {
  const double v1 = rng.Uniform(lo1, hi1);
  const double v0 = rng.Uniform(lo0, hi0);
  return {v0, v1};
}

inline Eigen::Vector2d NormalVector2(Rng& rng, double sigma0, double sigma1) {
  const double v1 = rng.Normal(0.0, sigma1);
  const double v0 = rng.Normal(0.0, sigma0);
  return {v0, v1};
}

inline Eigen::Vector3d UniformVector3(Rng& rng, const Eigen::Vector3d& lo,
                                      const Eigen::Vector3d& hi) {
  const double v2 = rng.Uniform(lo[2], hi[2]);
  const double v1 = rng.Uniform(lo[1], hi[1]);
  const double v0 = rng.Uniform(lo[0], hi[0]);
  return {v0, v1, v2};
}

inline Eigen::Vector3d NormalVector3(Rng& rng, double sigma0, double sigma1, double sigma2) {
  const double v2 = rng.Normal(0.0, sigma2);
  const double v1 = rng.Normal(0.0, sigma1);
  const double v0 = rng.Normal(0.0, sigma0);
  return {v0, v1, v2};
}

}  // namespace slamkit::testing
