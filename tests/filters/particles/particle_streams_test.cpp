#include "slamkit/filters/particles/particle_streams.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <set>
#include <vector>

namespace slamkit {
namespace {

// What every particle draws at every step, with `threads` threads.
std::vector<double> DrawAll(std::uint64_t seed, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  constexpr int kParticles = 16, kSteps = 5;
  const ParticleStreams streams(seed, kParticles);
  std::vector<double> out(kParticles * kSteps);
  for (int t = 0; t < kSteps; ++t) {
    tbb::parallel_for(0, kParticles, [&](int k) {
      Rng rng = streams.ForParticle(t, k);
      const double normal = rng.Normal();
      out[t * kParticles + k] = normal + rng.Uniform();
    });
  }
  return out;
}

TEST(ParticleStreams, SameSeedSameDrawsForAnyThreadCount) {
  const std::vector<double> one = DrawAll(7, 1);
  EXPECT_EQ(one, DrawAll(7, 2));
  EXPECT_EQ(one, DrawAll(7, 4));
  EXPECT_NE(one, DrawAll(8, 2));
}

TEST(ParticleStreams, EveryParticleAndStepHasItsOwnStream) {
  const ParticleStreams streams(3, 10);
  std::set<std::uint64_t> first;
  for (int t = 0; t < 20; ++t) {
    for (int k = 0; k < 10; ++k) first.insert(streams.ForParticle(t, k).NextU64());
  }
  EXPECT_EQ(first.size(), 200u);
  // Stream 1 + t · N + k of Rng::ForStream; the filter's own stream is 0.
  EXPECT_EQ(streams.ForParticle(4, 6).NextU64(), Rng::ForStream(3, 47).NextU64());
  ParticleStreams copy(3, 10);
  EXPECT_EQ(copy.filter().NextU64(), Rng::ForStream(3, 0).NextU64());
}

}  // namespace
}  // namespace slamkit
