#include "slamkit/planning/kmeans.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace slamkit {
namespace {

using Points = std::span<const Eigen::Vector2d>;

double SquaredDistanceToNearest(const Eigen::Vector2d& p,
                                const std::vector<Eigen::Vector2d>& centres) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& c : centres) best = std::min(best, (p - c).squaredNorm());
  return best;
}

// Index of the first point whose cumulative weight exceeds `u` × total: one draw in proportion
// to `weights` that does not depend on the standard library's distributions.
std::size_t DrawProportional(const std::vector<double>& weights, double total, Rng& rng) {
  const double target = rng.Uniform() * total;
  double sum = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    sum += weights[i];
    if (sum > target) return i;
  }
  return weights.size() - 1;  // rounding at the very end of the sum
}

// Seed 001 Sec. 3.1, Step 1 chooses the initial centres at random among the points; k-means++
// draws each next one with probability ∝ the squared distance to the nearest centre so far,
// which keeps well-separated clusters from sharing an initial centre. Points that coincide with
// a centre have weight 0, so duplicates never become two centres while other points remain.
std::vector<Eigen::Vector2d> SeedPlusPlus(Points points, int k, Rng& rng) {
  const auto n = points.size();
  std::vector<Eigen::Vector2d> centres;
  centres.push_back(points[std::min(static_cast<std::size_t>(rng.Uniform() * double(n)), n - 1)]);
  std::vector<double> weights(n);
  while (static_cast<int>(centres.size()) < k) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      weights[i] = SquaredDistanceToNearest(points[i], centres);
      total += weights[i];
    }
    if (total <= 0.0) break;  // fewer distinct points than k: no centre left to add
    centres.push_back(points[DrawProportional(weights, total, rng)]);
  }
  return centres;
}

// Step 2: each point to its nearest centre (the lowest index among equals). Returns whether any
// assignment changed.
bool AssignToNearest(Points points, const std::vector<Eigen::Vector2d>& centres,
                     std::vector<int>& assignment) {
  bool changed = false;
  for (std::size_t i = 0; i < points.size(); ++i) {
    int best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < centres.size(); ++c) {
      const double d2 = (points[i] - centres[c]).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best = static_cast<int>(c);
      }
    }
    changed = changed || assignment[i] != best;
    assignment[i] = best;
  }
  return changed;
}

// Step 3: each centre to the mean of its points; counts the points per cluster.
void UpdateCentres(Points points, const std::vector<int>& assignment,
                   std::vector<Eigen::Vector2d>& centres, std::vector<int>& sizes) {
  std::vector<Eigen::Vector2d> sums(centres.size(), Eigen::Vector2d::Zero());
  sizes.assign(centres.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    sums[assignment[i]] += points[i];
    ++sizes[assignment[i]];
  }
  for (std::size_t c = 0; c < centres.size(); ++c) {
    if (sizes[c] > 0) centres[c] = sums[c] / double(sizes[c]);
  }
}

}  // namespace

KMeansResult KMeans(Points points_m, const KMeansParams& params, Rng& rng) {
  if (points_m.empty()) throw std::invalid_argument("KMeans: no points");
  if (params.k < 1) throw std::invalid_argument("KMeans: k must be >= 1");
  const int k = std::min<int>(params.k, static_cast<int>(points_m.size()));
  KMeansResult out;
  out.centres_m = SeedPlusPlus(points_m, k, rng);
  out.assignment.assign(points_m.size(), -1);
  // Step 4: repeat Steps 2 and 3 until the assignment settles or the iteration limit.
  while (out.iterations < std::max(1, params.max_iterations)) {
    ++out.iterations;
    if (!AssignToNearest(points_m, out.centres_m, out.assignment)) {
      out.converged = true;
      break;
    }
    // The first assignment always changes (from -1), so sizes are set whatever the limit.
    UpdateCentres(points_m, out.assignment, out.centres_m, out.sizes);
  }
  return out;
}

int LargestCluster(const KMeansResult& result) {
  const auto it = std::max_element(result.sizes.begin(), result.sizes.end());
  return it == result.sizes.end() ? -1 : static_cast<int>(it - result.sizes.begin());
}

}  // namespace slamkit
