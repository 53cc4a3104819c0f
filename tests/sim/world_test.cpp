#include "slamkit/sim/world.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <cmath>
#include <numbers>

namespace slamkit {
namespace {

void ExpectIdsAreZeroToN(const LandmarkWorld& world) {
  for (std::size_t i = 0; i < world.landmarks.size(); ++i) {
    EXPECT_EQ(world.landmarks[i].id, static_cast<LandmarkId>(i));
  }
}

bool SameWorld(const LandmarkWorld& a, const LandmarkWorld& b) {
  if (a.landmarks.size() != b.landmarks.size()) return false;
  for (std::size_t i = 0; i < a.landmarks.size(); ++i) {
    if (a.landmarks[i].id != b.landmarks[i].id) return false;
    if (a.landmarks[i].position_m != b.landmarks[i].position_m) return false;
  }
  return true;
}

TEST(UniformWorld, CountIdsAndBounds) {
  UniformWorldParams params;
  params.min_xy_m = {-5.0, 10.0};
  params.max_xy_m = {25.0, 20.0};
  params.count = 400;
  Rng rng(3);
  const LandmarkWorld world = GenerateUniformWorld(params, rng);
  ASSERT_EQ(world.landmarks.size(), 400u);
  ExpectIdsAreZeroToN(world);
  Eigen::Vector2d lo = world.landmarks[0].position_m, hi = lo;
  for (const Landmark& l : world.landmarks) {
    EXPECT_GE(l.position_m.x(), -5.0);
    EXPECT_LT(l.position_m.x(), 25.0);
    EXPECT_GE(l.position_m.y(), 10.0);
    EXPECT_LT(l.position_m.y(), 20.0);
    lo = lo.cwiseMin(l.position_m);
    hi = hi.cwiseMax(l.position_m);
  }
  // 400 uniform samples cover the rectangle: the extremes lie close to its edges.
  EXPECT_LT(lo.x(), -4.0);
  EXPECT_GT(hi.x(), 24.0);
  EXPECT_LT(lo.y(), 10.5);
  EXPECT_GT(hi.y(), 19.5);
}

TEST(UniformWorld, CountFromDensity) {
  UniformWorldParams params;
  params.min_xy_m = {0.0, 0.0};
  params.max_xy_m = {30.0, 10.0};
  params.density_per_m2 = 0.1;  // 300 m² → 30 landmarks
  Rng rng(1);
  EXPECT_EQ(GenerateUniformWorld(params, rng).landmarks.size(), 30u);
  params.count = 7;  // an explicit count wins
  EXPECT_EQ(GenerateUniformWorld(params, rng).landmarks.size(), 7u);
}

TEST(ClusteredWorld, CountsIdsAndSpreadPerCluster) {
  std::vector<ClusterParams> clusters(2);
  clusters[0].center_m = {10.0, -20.0};
  clusters[0].sigma_m = 2.0;
  clusters[0].count = 500;
  clusters[1].center_m = {-30.0, 40.0};
  clusters[1].sigma_m = 5.0;
  clusters[1].density_per_m2 = 0.5;  // π (2σ)² × 0.5 = 157.08 → 157
  Rng rng(11);
  const LandmarkWorld world = GenerateClusteredWorld(clusters, rng);
  ASSERT_EQ(world.landmarks.size(), 657u);
  ExpectIdsAreZeroToN(world);
  const int first[] = {0, 500}, last[] = {500, 657};
  for (int c = 0; c < 2; ++c) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    double sum_sq = 0.0;
    for (int i = first[c]; i < last[c]; ++i) sum += world.landmarks[i].position_m;
    const int n = last[c] - first[c];
    const Eigen::Vector2d mean = sum / n;
    for (int i = first[c]; i < last[c]; ++i) {
      sum_sq += (world.landmarks[i].position_m - mean).squaredNorm();
    }
    const double sigma = clusters[c].sigma_m;
    EXPECT_LT((mean - clusters[c].center_m).norm(), 4.0 * sigma / std::sqrt(n));
    EXPECT_NEAR(std::sqrt(sum_sq / (2.0 * (n - 1))), sigma, 0.15 * sigma);
  }
}

TEST(World, SameSeedSameWorldOtherSeedOtherWorld) {
  WorldSpec spec;
  spec.uniform.count = 50;
  spec.seed = 42;
  EXPECT_TRUE(SameWorld(MakeWorld(spec), MakeWorld(spec)));
  Rng rng(42);
  EXPECT_TRUE(SameWorld(MakeWorld(spec), GenerateUniformWorld(spec.uniform, rng)));
  WorldSpec other = spec;
  other.seed = 43;
  EXPECT_FALSE(SameWorld(MakeWorld(spec), MakeWorld(other)));

  spec.kind = WorldSpec::Kind::kClusters;
  spec.clusters.resize(1);
  spec.clusters[0].count = 20;
  other = spec;
  other.seed = 43;
  EXPECT_TRUE(SameWorld(MakeWorld(spec), MakeWorld(spec)));
  EXPECT_FALSE(SameWorld(MakeWorld(spec), MakeWorld(other)));
}

TEST(World, GivenWorldIsCopied) {
  WorldSpec spec;
  spec.kind = WorldSpec::Kind::kGiven;
  spec.given.landmarks = {{7, {1.0, 2.0}}, {3, {-4.0, 5.0}}};
  EXPECT_TRUE(SameWorld(MakeWorld(spec), spec.given));
}

}  // namespace
}  // namespace slamkit

// Issue 8, item 5: a landmark count beyond WorldSpec::max_landmarks throws before allocating.
TEST(WorldLimits, HugeCountsAndDensitiesAreRejected) {
  slamkit::Rng rng(1);
  slamkit::UniformWorldParams uniform;
  uniform.count = 2000000000;
  EXPECT_THROW(slamkit::GenerateUniformWorld(uniform, rng), std::length_error);
  uniform.count = 0;
  uniform.density_per_m2 = 1e6;
  try {
    slamkit::GenerateUniformWorld(uniform, rng);
    FAIL();
  } catch (const std::length_error& e) {
    EXPECT_NE(std::string(e.what()).find("max_landmarks"), std::string::npos) << e.what();
  }
  uniform.density_per_m2 = 1e300;
  EXPECT_THROW(slamkit::GenerateUniformWorld(uniform, rng), std::length_error);
  slamkit::ClusterParams cluster;
  cluster.density_per_m2 = 1e6;
  EXPECT_THROW(slamkit::GenerateClusteredWorld({cluster}, rng), std::length_error);
  slamkit::WorldSpec spec;
  spec.uniform.count = 2000000000;
  EXPECT_THROW(slamkit::MakeWorld(spec), std::length_error);
  spec.uniform.count = 200;
  spec.max_landmarks = 100;
  EXPECT_THROW(slamkit::MakeWorld(spec), std::length_error);
  spec.max_landmarks = 200;
  EXPECT_EQ(slamkit::MakeWorld(spec).landmarks.size(), 200u);
}
