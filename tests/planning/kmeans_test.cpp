#include <gtest/gtest.h>

#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/rng.hpp"
#include "slamkit/planning/kmeans.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

struct Labelled {
  std::vector<Eigen::Vector2d> points;
  std::vector<int> labels;
};

// Three clusters of σ = 1 m, 20 m apart, of 25, 30 and 35 points.
const std::vector<Eigen::Vector2d> kCentres = {{0.0, 0.0}, {20.0, 0.0}, {5.0, 20.0}};

Labelled SeparatedClusters(std::uint64_t seed) {
  Rng rng(seed);
  Labelled out;
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 25 + 5 * c; ++i) {
      out.points.push_back(kCentres[c] + testing::NormalVector2(rng, 1.0, 1.0));
      out.labels.push_back(c);
    }
  }
  return out;
}

TEST(KMeans, RecoversWellSeparatedClustersForSeveralSeeds) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const Labelled data = SeparatedClusters(seed);
    Rng rng(100 + seed);
    const KMeansResult r = KMeans(data.points, {}, rng);
    ASSERT_EQ(r.centres_m.size(), 3u) << "seed " << seed;
    EXPECT_TRUE(r.converged) << "seed " << seed;
    // The assignment is exact up to a permutation of the labels.
    std::map<int, int> true_of_found;
    for (std::size_t i = 0; i < data.points.size(); ++i) {
      const auto [it, inserted] = true_of_found.emplace(r.assignment[i], data.labels[i]);
      EXPECT_EQ(it->second, data.labels[i]) << "seed " << seed << " point " << i;
    }
    std::set<int> distinct;
    for (const auto& [found, truth] : true_of_found) distinct.insert(truth);
    ASSERT_EQ(distinct.size(), 3u) << "seed " << seed;
    for (const auto& [found, truth] : true_of_found) {
      // The mean of 25+ samples of σ = 1 m lies within 0.8 m (4 standard errors per axis).
      EXPECT_LT((r.centres_m[found] - kCentres[truth]).norm(), 0.8) << "seed " << seed;
      EXPECT_EQ(r.sizes[found], 25 + 5 * truth) << "seed " << seed;
    }
    EXPECT_EQ(true_of_found.at(LargestCluster(r)), 2) << "seed " << seed;
  }
}

TEST(KMeans, SeedingIsDeterministicPerSeedAndDependsOnIt) {
  // Uniform points: no clear clusters, so the result shows the seeding.
  Rng data_rng(3);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 200; ++i) points.push_back(testing::UniformVector2(data_rng, 0, 50, 0, 50));
  const KMeansParams seeding_only{5, 1};
  std::set<std::vector<double>> different;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    Rng a(seed), b(seed);
    const KMeansResult ra = KMeans(points, seeding_only, a);
    const KMeansResult rb = KMeans(points, seeding_only, b);
    ASSERT_EQ(ra.centres_m.size(), 5u);
    EXPECT_EQ(ra.assignment, rb.assignment);
    std::vector<double> flat;
    for (std::size_t c = 0; c < ra.centres_m.size(); ++c) {
      EXPECT_EQ(ra.centres_m[c], rb.centres_m[c]);  // bit for bit
      flat.push_back(ra.centres_m[c].x());
      flat.push_back(ra.centres_m[c].y());
    }
    different.insert(flat);
  }
  EXPECT_EQ(different.size(), 5u);
}

TEST(KMeans, StopsAtTheIterationLimit) {
  Rng data_rng(9);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 300; ++i) points.push_back(testing::UniformVector2(data_rng, 0, 50, 0, 50));
  Rng rng(1);
  const KMeansResult limited = KMeans(points, {8, 2}, rng);
  EXPECT_EQ(limited.iterations, 2);
  EXPECT_FALSE(limited.converged);
  Rng rng2(1);
  const KMeansResult free = KMeans(points, {8, 1000}, rng2);
  EXPECT_TRUE(free.converged);
  EXPECT_GT(free.iterations, 2);
  EXPECT_LT(free.iterations, 1000);
}

TEST(KMeans, FewerDistinctPointsThanKGiveFewerClustersAndBadInputThrows) {
  const std::vector<Eigen::Vector2d> points = {{1, 1}, {1, 1}, {4, 4}};
  Rng rng(1);
  const KMeansResult r = KMeans(points, {5, 10}, rng);
  ASSERT_EQ(r.centres_m.size(), 2u);
  EXPECT_EQ(r.assignment[0], r.assignment[1]);
  EXPECT_NE(r.assignment[0], r.assignment[2]);
  EXPECT_EQ(r.centres_m[LargestCluster(r)], Eigen::Vector2d(1, 1));
  EXPECT_THROW(KMeans(std::vector<Eigen::Vector2d>{}, {}, rng), std::invalid_argument);
  EXPECT_THROW(KMeans(points, {0, 10}, rng), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
