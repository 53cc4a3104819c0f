#pragma once

#include <algorithm>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/particles/resampling.hpp"

namespace slamkit {

// When and how a particle set resamples: adaptively, when N_eff / N falls below `threshold`
// (Doucet et al.; GMapping's resampleThreshold), by `scheme`.
struct ResamplingParams {
  double threshold = 0.5;
  ResamplingScheme scheme = ResamplingScheme::kSystematic;
};

// The particles of a particle filter with their log-weights: what every particle filter shares
// (the grid RBPF, FastSLAM). `P` is whatever one particle holds (pose, map, path); it is copied
// when resampling duplicates it, so it should share its bulk (copy-on-write maps, PathTree). Each
// particle carries two log-weights: the one since the last resampling, which decides the next
// resampling, and the sum over its whole history, which picks the best particle and is kept by
// copies.
template <class P>
class ParticleSet {
 public:
  ParticleSet() = default;
  // `n` copies of `first` (at least one), all weights zero.
  ParticleSet(int n, const P& first) { Assign(n, first); }

  void Assign(int n, const P& first) {
    n = std::max(n, 1);
    particles_.assign(n, first);
    log_weights_.assign(n, 0.0);
    total_log_weights_.assign(n, 0.0);
    sources_.resize(n);
    for (int i = 0; i < n; ++i) sources_[i] = i;
  }

  int size() const { return static_cast<int>(particles_.size()); }
  bool empty() const { return particles_.empty(); }
  P& operator[](int i) { return particles_[i]; }
  const P& operator[](int i) const { return particles_[i]; }

  // Multiplies particle i's weight by exp(log_factor). Safe in parallel for distinct i.
  void AddLogWeight(int i, double log_factor) {
    log_weights_[i] += log_factor;
    total_log_weights_[i] += log_factor;
  }
  std::span<const double> log_weights() const { return log_weights_; }
  double total_log_weight(int i) const { return total_log_weights_[i]; }

  // The normalised weights of the log-weights since the last resampling, scaled by `gain` (a gain
  // below 1 flattens them: GMapping's likelihood gain).
  std::vector<double> Weights(double gain = 1.0) const {
    return NormaliseLogWeights(log_weights_, gain);
  }
  double EffectiveSampleSize(double gain = 1.0) const {
    return slamkit::EffectiveSampleSize(Weights(gain));
  }

  // The particle with the largest total log-weight (the first of equals).
  int Best() const {
    int best = 0;
    for (int i = 1; i < size(); ++i) {
      if (total_log_weights_[i] > total_log_weights_[best]) best = i;
    }
    return best;
  }

  // Normalises the weights with `gain`, records N_eff and, if N_eff < threshold · N, replaces the
  // set by the particles the scheme draws (copies; weights since resampling reset to zero).
  // Returns whether it resampled. Afterwards source(i) tells where particle i came from (i itself
  // when nothing was resampled).
  bool ResampleIfNeeded(double gain, const ResamplingParams& params, Rng& rng) {
    const std::vector<double> weights = Weights(gain);
    ++decisions_;
    if (first_unnormalised_ == 0 && !WeightsNormalise(weights)) first_unnormalised_ = decisions_;
    last_neff_ = slamkit::EffectiveSampleSize(weights);
    for (int i = 0; i < size(); ++i) sources_[i] = i;
    if (last_neff_ >= params.threshold * double(size())) return false;
    Keep(Resample(params.scheme, weights, rng));
    return true;
  }

  // Replaces the set by copies of the particles `keep` (one index per new particle). The copies
  // go to buffers kept from the last call: a fresh particle array at every resampling is a large
  // allocation, which makes glibc's malloc consolidate every small block freed since the last one
  // (for FastSLAM, thousands of tree nodes scattered over the heap: a cost that grew with the map).
  void Keep(std::span<const int> keep) {
    next_.clear();
    next_totals_.clear();
    for (int k : keep) {
      next_.push_back(particles_[k]);
      next_totals_.push_back(total_log_weights_[k]);
    }
    particles_.swap(next_);
    total_log_weights_.swap(next_totals_);
    next_.clear();  // releases the particles replaced (their shared maps and paths)
    log_weights_.assign(particles_.size(), 0.0);
    sources_.assign(keep.begin(), keep.end());
  }

  // CheckLogWeights() of the weights since resampling (with `gain`) and of the totals, and
  // whether every resampling decision had weights that normalised (resampling on NaN weights
  // keeps copies of healthy particles, so the weights alone no longer show it): throws
  // NumericalError "`where`: …" naming the particle or the decision. O(N).
  void CheckHealth(double gain, std::string_view where) const {
    CheckLogWeights(log_weights_, gain, "log-weight", where);
    CheckLogWeights(total_log_weights_, 1.0, "total log-weight", where);
    CheckNormalisedAtResampling(first_unnormalised_, where);
  }

  int source(int i) const { return sources_[i]; }
  double last_neff() const { return last_neff_; }

 private:
  std::vector<P> particles_;
  std::vector<double> log_weights_;        // since the last resampling
  std::vector<double> total_log_weights_;  // over the particle's whole history
  std::vector<int> sources_;
  std::vector<P> next_;  // Keep()'s buffers, empty between calls
  std::vector<double> next_totals_;
  double last_neff_ = 0.0;
  long decisions_ = 0;           // ResampleIfNeeded() calls
  long first_unnormalised_ = 0;  // the first whose weights did not normalise (1, 2, …); 0: none
};

}  // namespace slamkit
