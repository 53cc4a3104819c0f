#pragma once

#include <cmath>
#include <span>

namespace slamkit {

// One figure over the runs of an experiment (a policy's seeds, a log's seeds, a method's Monte
// Carlo runs): how many, their mean, the unbiased sample variance (n − 1; 0 for one value), the
// smallest and the largest. Every value counts, NaN included, so a diverged run shows instead of
// vanishing; a caller that means "the runs that have this figure" selects them first.
struct Spread {
  int count = 0;
  double mean = NAN;  // NaN, as min and max, for no value
  double variance = 0.0;
  double min = NAN;
  double max = NAN;

  double sd() const { return std::sqrt(variance); }
};

Spread SpreadOf(std::span<const double> values);

}  // namespace slamkit
