#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>

namespace slamkit {

// The only source of randomness in slamkit. Every algorithm that samples takes an Rng& so that a
// seed fixes the output bit for bit. Normal samples use our own Box-Muller transform rather than
// std::normal_distribution, whose algorithm differs between standard libraries.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // An independent stream for run `stream` of an experiment seeded with `master_seed`, so that
  // Monte Carlo run k draws the same numbers whichever thread runs it.
  static Rng ForStream(std::uint64_t master_seed, std::uint64_t stream);

  double Uniform(double lo = 0.0, double hi = 1.0);
  double Normal(double mean = 0.0, double stddev = 1.0);
  // A sample of N(0, cov) drawn through the Cholesky factor of `cov` (positive semi-definite).
  Eigen::VectorXd MultivariateNormal(const Eigen::MatrixXd& cov);
  std::uint64_t NextU64() { return engine_(); }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace slamkit
