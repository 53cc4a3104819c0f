#pragma once

#include <span>
#include <vector>

#include "slamkit/core/rng.hpp"

namespace slamkit {

// Effective sample size 1 / Σ w² of normalised weights.
double EffectiveSampleSize(std::span<const double> weights);

// Normalised weights from log-weights scaled by `gain` (softmax, stable for large magnitudes).
std::vector<double> NormaliseLogWeights(std::span<const double> log_weights, double gain = 1.0);

// Systematic (low-variance) resampling: the indices of the particles to keep, one per particle,
// in increasing order. One uniform draw from `rng`.
std::vector<int> SystematicResample(std::span<const double> weights, Rng& rng);

}  // namespace slamkit
