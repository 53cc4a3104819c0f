#include "slamkit/sim/world.hpp"

#include <cmath>
#include <numbers>

namespace slamkit {
namespace {

// An explicit count wins; otherwise the density over `area_m2`, rounded.
int LandmarkCount(int count, double density_per_m2, double area_m2) {
  if (count > 0) return count;
  return static_cast<int>(std::lround(density_per_m2 * area_m2));
}

}  // namespace

LandmarkWorld GenerateUniformWorld(const UniformWorldParams& params, Rng& rng) {
  const Eigen::Vector2d size = params.max_xy_m - params.min_xy_m;
  const int count = LandmarkCount(params.count, params.density_per_m2, size.x() * size.y());
  LandmarkWorld world;
  world.landmarks.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double x = rng.Uniform(params.min_xy_m.x(), params.max_xy_m.x());
    const double y = rng.Uniform(params.min_xy_m.y(), params.max_xy_m.y());
    world.landmarks.push_back({i, {x, y}});
  }
  return world;
}

LandmarkWorld GenerateClusteredWorld(const std::vector<ClusterParams>& clusters, Rng& rng) {
  LandmarkWorld world;
  LandmarkId next_id = 0;
  for (const ClusterParams& cluster : clusters) {
    const double radius_m = 2.0 * cluster.sigma_m;
    const int count = LandmarkCount(cluster.count, cluster.density_per_m2,
                                    std::numbers::pi * radius_m * radius_m);
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
    case WorldSpec::Kind::kUniform:
      return GenerateUniformWorld(spec.uniform, rng);
    case WorldSpec::Kind::kClusters:
      return GenerateClusteredWorld(spec.clusters, rng);
    case WorldSpec::Kind::kGiven:
      return spec.given;
  }
  return {};
}

}  // namespace slamkit
