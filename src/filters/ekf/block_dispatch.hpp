#pragma once

#include <type_traits>

#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit::internal {

// Calls f(std::integral_constant<int, d>) for d in 1..kMaxBlockDim, so that the small matrices of
// an update have fixed sizes (stack storage, unrolled products) whatever the block kind.
template <typename F>
decltype(auto) WithDim(int d, F&& f) {
  static_assert(kMaxBlockDim == 3, "extend the cases below");
  switch (d) {
    case 1:
      return f(std::integral_constant<int, 1>{});
    case 2:
      return f(std::integral_constant<int, 2>{});
    default:
      return f(std::integral_constant<int, 3>{});
  }
}

// Calls f(D0, D1) with the two dimensions as integral constants (a two-block observation).
template <typename F>
decltype(auto) WithDims(int d0, int d1, F&& f) {
  return WithDim(d0, [&](auto D0) { return WithDim(d1, [&](auto D1) { return f(D0, D1); }); });
}

}  // namespace slamkit::internal
