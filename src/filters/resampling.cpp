#include "slamkit/filters/resampling.hpp"

#include <algorithm>
#include <cmath>

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

// Probabilistic Robotics, Table 4.4 (low-variance sampler).
std::vector<int> SystematicResample(std::span<const double> weights, Rng& rng) {
  const int n = static_cast<int>(weights.size());
  std::vector<int> keep;
  keep.reserve(n);
  const double step = 1.0 / n;
  double u = rng.Uniform(0.0, step);
  double cumulative = weights.empty() ? 0.0 : weights[0];
  int i = 0;
  for (int k = 0; k < n; ++k) {
    while (u > cumulative && i + 1 < n) cumulative += weights[++i];
    keep.push_back(i);
    u += step;
  }
  return keep;
}

}  // namespace slamkit
