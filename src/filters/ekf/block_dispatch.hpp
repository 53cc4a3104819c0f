#pragma once

#include <Eigen/Core>
#include <type_traits>

#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit::internal {

// The small matrices of an update get fixed sizes (stack storage, unrolled products) for what
// every shipped model uses: 2-D measurements of 2-D and 3-D blocks. Any other combination (a
// 1-D block, a 1-D or 3-D measurement) runs the same code at dynamic sizes (Eigen::Dynamic, at
// most kMaxBlockDim): one instantiation instead of one per combination, which had made these
// units the longest of the build.
inline constexpr int kDynamicDim = Eigen::Dynamic;

inline constexpr bool IsFixedBlockDim(int d) { return d == 2 || d == 3; }

// f(integral_constant<int, d>) for d = 2 or 3 when `fixed`, else f(integral_constant<int,
// Dynamic>).
template <bool kFixed = true, typename F>
decltype(auto) WithDim(int d, F&& f) {
  static_assert(kMaxBlockDim == 3, "extend the cases below");
  if constexpr (kFixed) {
    if (d == 2) return f(std::integral_constant<int, 2>{});
    if (d == 3) return f(std::integral_constant<int, 3>{});
  }
  return f(std::integral_constant<int, kDynamicDim>{});
}

// f(D0, D1): both fixed when `fixed` and both are 2 or 3, else both dynamic.
template <bool kFixed = true, typename F>
decltype(auto) WithDims(int d0, int d1, F&& f) {
  if constexpr (kFixed) {
    if (IsFixedBlockDim(d0) && IsFixedBlockDim(d1)) {
      return WithDim(d0, [&](auto D0) { return WithDim(d1, [&](auto D1) { return f(D0, D1); }); });
    }
  }
  return f(std::integral_constant<int, kDynamicDim>{}, std::integral_constant<int, kDynamicDim>{});
}

// A measurement's dimension: 2 fixed, anything else dynamic.
template <typename F>
decltype(auto) WithMeasurementDim(int z, F&& f) {
  if (z == 2) return f(std::integral_constant<int, 2>{});
  return f(std::integral_constant<int, kDynamicDim>{});
}

}  // namespace slamkit::internal
