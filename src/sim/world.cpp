#include "slamkit/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <vector>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace slamkit {
namespace {

// An explicit count wins; otherwise the density over `area_m2`, rounded. Throws before the
// conversion to int when the count would exceed `max_landmarks` (`so_far` already placed).
int LandmarkCount(int count, double density_per_m2, double area_m2, int max_landmarks,
                  double so_far = 0.0) {
  if (count <= 0 && !(density_per_m2 >= 0.0 && std::isfinite(density_per_m2))) {
    throw std::invalid_argument("world: density_per_m2 must be finite and >= 0, not " +
                                std::to_string(density_per_m2));
  }
  const double n = count > 0 ? double(count) : std::round(density_per_m2 * area_m2);
  if (!(n + so_far <= double(max_landmarks))) {
    throw std::length_error(
        "world: " + (std::ostringstream() << std::setprecision(12) << n + so_far).str() +
        " landmarks (count, or density_per_m2 x area) exceed the limit max_landmarks = " +
        std::to_string(max_landmarks) + "; raise WorldSpec::max_landmarks to allow more");
  }
  return static_cast<int>(n);
}

}  // namespace

LandmarkWorld GenerateUniformWorld(const UniformWorldParams& params, Rng& rng) {
  const Eigen::Vector2d size = params.max_xy_m - params.min_xy_m;
  const int count = LandmarkCount(params.count, params.density_per_m2, size.x() * size.y(),
                                  params.max_landmarks);
  LandmarkWorld world;
  world.landmarks.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double x = rng.Uniform(params.min_xy_m.x(), params.max_xy_m.x());
    const double y = rng.Uniform(params.min_xy_m.y(), params.max_xy_m.y());
    world.landmarks.push_back({i, {x, y}});
  }
  return world;
}

LandmarkWorld GenerateClusteredWorld(const std::vector<ClusterParams>& clusters, Rng& rng,
                                     int max_landmarks) {
  LandmarkWorld world;
  LandmarkId next_id = 0;
  std::vector<int> counts;
  double total = 0.0;
  for (const ClusterParams& cluster : clusters) {  // all counts checked before any allocation
    const double radius_m = 2.0 * cluster.sigma_m;
    counts.push_back(LandmarkCount(cluster.count, cluster.density_per_m2,
                                   std::numbers::pi * radius_m * radius_m, max_landmarks,
                                   total));
    total += counts.back();
  }
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const ClusterParams& cluster = clusters[c];
    const int count = counts[c];
    for (int i = 0; i < count; ++i) {
      const double x = rng.Normal(cluster.center_m.x(), cluster.sigma_m);
      const double y = rng.Normal(cluster.center_m.y(), cluster.sigma_m);
      world.landmarks.push_back({next_id++, {x, y}});
    }
  }
  return world;
}

LandmarkWorld MakeWorld(const WorldSpec& spec) {
  Rng rng(spec.seed);
  switch (spec.kind) {
    case WorldSpec::Kind::kUniform: {
      UniformWorldParams uniform = spec.uniform;
      uniform.max_landmarks = spec.max_landmarks;  // the spec's limit governs
      return GenerateUniformWorld(uniform, rng);
    }
    case WorldSpec::Kind::kClusters:
      return GenerateClusteredWorld(spec.clusters, rng, spec.max_landmarks);
    case WorldSpec::Kind::kGiven:
      return spec.given;
  }
  return {};
}

}  // namespace slamkit
