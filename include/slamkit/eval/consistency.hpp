#pragma once

namespace slamkit {

// Two-sided confidence band of a mean of `samples` independent χ²(dof) variables:
// [χ²_{samples·dof}((1−c)/2), χ²_{samples·dof}((1+c)/2)] / samples (Bar-Shalom et al., 2001).
// For 50 Monte Carlo runs of a 3-DoF pose at 95 %: [2.360, 3.716].
struct ChiSquareBand {
  double lo = 0.0;
  double hi = 0.0;
  bool Contains(double value) const { return value >= lo && value <= hi; }
};

ChiSquareBand AneesBand(int samples, int dof, double confidence = 0.95);

// χ² quantile with `dof` degrees of freedom (gates: ChiSquareQuantile(2, 0.99) = 9.21).
double ChiSquareQuantile(int dof, double probability);

}  // namespace slamkit
