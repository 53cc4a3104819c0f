#pragma once

#include <cstdint>

#include "slamkit/core/rng.hpp"

namespace slamkit {

// The random streams of a particle filter seeded with `seed`, so that a seed fixes the result
// whatever the thread count: particle k's draws at step t come from their own stream (made afresh,
// whichever thread runs the particle), and the filter's own draws (resampling), which run in
// sequence, from stream 0.
class ParticleStreams {
 public:
  ParticleStreams(std::uint64_t seed, int particles)
      : seed_(seed), particles_(particles), filter_(Rng::ForStream(seed, 0)) {}

  // Stream 1 + t · N + k of Rng::ForStream(seed, ·): distinct for every (t, k) with k < N.
  Rng ForParticle(int step, int k) const {
    return Rng::ForStream(seed_,
                          1 + std::uint64_t(step) * std::uint64_t(particles_) + std::uint64_t(k));
  }
  // The filter's own stream, one sequence over the whole run.
  Rng& filter() { return filter_; }

 private:
  std::uint64_t seed_;
  int particles_;
  Rng filter_;
};

}  // namespace slamkit
