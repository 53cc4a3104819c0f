#include "slamkit/eval/consistency.hpp"

#include <stdexcept>

#include <boost/math/distributions/chi_squared.hpp>

namespace slamkit {

double ChiSquareQuantile(int dof, double probability) {
  if (dof <= 0 || !(probability > 0.0 && probability < 1.0)) {
    throw std::invalid_argument("ChiSquareQuantile: dof must be > 0 and probability in (0, 1)");
  }
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof), probability);
}

ChiSquareBand AneesBand(int samples, int dof, double confidence) {
  const int total = samples * dof;
  const double tail = 0.5 * (1.0 - confidence);
  return {ChiSquareQuantile(total, tail) / samples, ChiSquareQuantile(total, 1.0 - tail) / samples};
}

}  // namespace slamkit
