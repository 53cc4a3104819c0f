#include "slamkit/filters/particles/resampling.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "slamkit/core/numerical_error.hpp"

namespace slamkit {

double EffectiveSampleSize(std::span<const double> weights) {
  double sum_sq = 0.0;
  for (double w : weights) sum_sq += w * w;
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

std::vector<double> NormaliseLogWeights(std::span<const double> log_weights, double gain) {
  std::vector<double> w(log_weights.size());
  if (w.empty()) return w;
  const double max = *std::max_element(log_weights.begin(), log_weights.end());
  double sum = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    w[i] = std::exp(gain * (log_weights[i] - max));
    sum += w[i];
  }
  for (double& v : w) v /= sum;
  return w;
}

void CheckLogWeights(std::span<const double> log_weights, double gain, std::string_view what,
                     std::string_view where) {
  const auto fail = [&](const std::string& problem) {
    throw NumericalError(std::string(where) + ": " + problem);
  };
  bool any_finite = false;
  for (std::size_t i = 0; i < log_weights.size(); ++i) {
    const double l = log_weights[i];
    if (std::isnan(l) || l == INFINITY) {
      fail("particle " + std::to_string(i) + "'s " + std::string(what) + " is " +
           (std::isnan(l) ? "nan" : "inf"));
    }
    any_finite = any_finite || std::isfinite(l);
  }
  if (log_weights.empty()) return;
  if (!any_finite) fail("every particle's " + std::string(what) + " is -inf");
  const std::vector<double> weights = NormaliseLogWeights(log_weights, gain);
  if (!WeightsNormalise(weights)) {
    double sum = 0.0;
    for (const double w : weights) sum += w;
    const std::string total = std::isnan(sum) ? "nan" : std::to_string(sum);
    fail("the normalised " + std::string(what) + "s sum to " + total);
  }
}

bool WeightsNormalise(std::span<const double> weights) {
  double sum = 0.0;
  for (const double w : weights) sum += w;
  return weights.empty() || std::abs(sum - 1.0) <= 1e-9;  // false for NaN
}

void CheckNormalisedAtResampling(long first_unnormalised, std::string_view where) {
  if (first_unnormalised == 0) return;
  throw NumericalError(std::string(where) +
                       ": the weights did not normalise at resampling decision " +
                       std::to_string(first_unnormalised));
}

namespace {

// The particle each of the increasing pointers `u` (in [0, 1)) falls on in the cumulative weights;
// the last particle takes what rounding leaves past the total.
std::vector<int> Invert(std::span<const double> weights, std::span<const double> u) {
  const int n = static_cast<int>(weights.size());
  std::vector<int> keep;
  keep.reserve(u.size());
  double cumulative = weights.empty() ? 0.0 : weights[0];
  int i = 0;
  for (double pointer : u) {
    while (pointer > cumulative && i + 1 < n) cumulative += weights[++i];
    keep.push_back(i);
  }
  return keep;
}

}  // namespace

// Probabilistic Robotics, Table 4.4 (low-variance sampler).
std::vector<int> SystematicResample(std::span<const double> weights, Rng& rng) {
  const int n = static_cast<int>(weights.size());
  std::vector<double> u(n);
  const double step = 1.0 / n;
  double pointer = n > 0 ? rng.Uniform(0.0, step) : 0.0;
  for (double& v : u) {
    v = pointer;
    pointer += step;
  }
  return Invert(weights, u);
}

std::vector<int> StratifiedResample(std::span<const double> weights, Rng& rng) {
  const int n = static_cast<int>(weights.size());
  std::vector<double> u(n);
  for (int k = 0; k < n; ++k) u[k] = (k + rng.Uniform()) / n;
  return Invert(weights, u);
}

std::vector<int> MultinomialResample(std::span<const double> weights, Rng& rng) {
  std::vector<double> u(weights.size());
  for (double& v : u) v = rng.Uniform();
  std::sort(u.begin(), u.end());
  return Invert(weights, u);
}

std::vector<int> Resample(ResamplingScheme scheme, std::span<const double> weights, Rng& rng) {
  switch (scheme) {
    case ResamplingScheme::kStratified:
      return StratifiedResample(weights, rng);
    case ResamplingScheme::kMultinomial:
      return MultinomialResample(weights, rng);
    case ResamplingScheme::kSystematic:
      break;
  }
  return SystematicResample(weights, rng);
}

}  // namespace slamkit
