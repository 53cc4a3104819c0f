#include "slamkit/eval/spread.hpp"

#include <algorithm>
#include <numeric>

namespace slamkit {

Spread SpreadOf(std::span<const double> values) {
  Spread s;
  if (values.empty()) return s;
  s.count = static_cast<int>(values.size());
  const double n = static_cast<double>(values.size());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  if (values.size() > 1) {
    double squares = 0.0;
    for (const double v : values) squares += (v - s.mean) * (v - s.mean);
    s.variance = squares / (n - 1.0);
  }
  // std::minmax_element would skip past a NaN; a NaN value makes the extremes NaN too.
  s.min = values.front();
  s.max = values.front();
  for (const double v : values) {
    if (std::isnan(v) || std::isnan(s.min)) {
      s.min = s.max = NAN;
      break;
    }
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
  }
  return s;
}

}  // namespace slamkit
