#include "slamkit/maps/landmark_map.hpp"

namespace slamkit {

std::optional<int> LandmarkMap::FindBySource(LandmarkId id) const {
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    if (landmarks[i].source_id == id) return static_cast<int>(i);
  }
  return std::nullopt;
}

}  // namespace slamkit
