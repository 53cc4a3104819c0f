#pragma once

#include <cstdint>

namespace slamkit {

// Identifier of a landmark in the world or a data set (not its index in a filter's state).
using LandmarkId = std::int64_t;
inline constexpr LandmarkId kNoLandmark = -1;

}  // namespace slamkit
