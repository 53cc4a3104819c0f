#include "slamkit/core/rng.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>

namespace slamkit {
namespace {

// SplitMix64 finaliser: spreads nearby (seed, stream) pairs over the whole 64-bit space.
std::uint64_t Mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

Rng Rng::ForStream(std::uint64_t master_seed, std::uint64_t stream) {
  return Rng(Mix(Mix(master_seed) ^ (stream * 0xd1b54a32d192ed03ULL + 1)));
}

double Rng::Uniform(double lo, double hi) {
  // 53 random bits give every double in [0, 1) with equal spacing.
  const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * u;
}

double Rng::Normal(double mean, double stddev) {
  if (has_spare_) {
    has_spare_ = false;
    return mean + stddev * spare_;
  }
  double u1 = Uniform();
  while (u1 <= 0.0) u1 = Uniform();
  const double u2 = Uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 2.0 * std::numbers::pi * u2;
  spare_ = r * std::sin(a);
  has_spare_ = true;
  return mean + stddev * r * std::cos(a);
}

Eigen::VectorXd Rng::MultivariateNormal(const Eigen::MatrixXd& cov) {
  Eigen::VectorXd w(cov.rows());
  for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = Normal();
  // LDLT tolerates singular covariances (a noise-free component).
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(cov);
  const Eigen::VectorXd d = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
  Eigen::VectorXd y = ldlt.matrixL() * (d.asDiagonal() * w);
  return ldlt.transpositionsP().transpose() * y;
}

}  // namespace slamkit
