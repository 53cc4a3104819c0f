#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "slamkit/core/rng.hpp"

namespace slamkit {

// Effective sample size 1 / Σ w² of normalised weights.
double EffectiveSampleSize(std::span<const double> weights);

// Normalised weights from log-weights scaled by `gain` (softmax, stable for large magnitudes).
std::vector<double> NormaliseLogWeights(std::span<const double> log_weights, double gain = 1.0);

// The health of a particle filter's log-weights (`what`, e.g. "log-weight"): each finite or −∞ (a
// particle ruled out), at least one finite, and the normalised weights (with `gain`) finite and
// summing to 1 within 1e-9. Throws NumericalError "`where`: …" naming the particle. O(N).
void CheckLogWeights(std::span<const double> log_weights, double gain, std::string_view what,
                     std::string_view where);

// Whether normalised `weights` are finite and sum to 1 within 1e-9. O(N).
bool WeightsNormalise(std::span<const double> weights);
// Throws NumericalError "`where`: the weights did not normalise at resampling decision k" unless
// `first_unnormalised` (k) is 0.
void CheckNormalisedAtResampling(long first_unnormalised, std::string_view where);

// Each scheme returns the indices of the particles to keep, one per particle, in increasing order;
// particle i is kept about N · w_i times. They differ in how much that count varies.
enum class ResamplingScheme {
  // Thrun's low-variance sampler: one uniform draw, then N equally spaced pointers. Particle i is
  // kept ⌊N w_i⌋ or ⌈N w_i⌉ times.
  kSystematic,
  // One uniform draw in each of the N strata [k/N, (k+1)/N): N draws, less variance than
  // multinomial, a little more than systematic.
  kStratified,
  // N independent draws from the weights (the textbook bootstrap filter): the most variance.
  kMultinomial,
};

// Probabilistic Robotics, Table 4.4 (low-variance sampler). One uniform draw from `rng`.
std::vector<int> SystematicResample(std::span<const double> weights, Rng& rng);
// N uniform draws from `rng`, one per stratum.
std::vector<int> StratifiedResample(std::span<const double> weights, Rng& rng);
// N uniform draws from `rng`, each inverted through the cumulative weights.
std::vector<int> MultinomialResample(std::span<const double> weights, Rng& rng);

std::vector<int> Resample(ResamplingScheme scheme, std::span<const double> weights, Rng& rng);

}  // namespace slamkit
