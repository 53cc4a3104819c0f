#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"

namespace slamkit {

// A point landmark as estimated by a filter.
struct MappedLandmark {
  LandmarkId source_id = kNoLandmark;  // id of the sighting that created it, if known
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

struct LandmarkMap {
  std::vector<MappedLandmark> landmarks;

  // Index of the landmark created from id `id`, if any (linear search: maps are output, not a
  // hot path).
  std::optional<int> FindBySource(LandmarkId id) const;
};

// The map as a filter held it at time t_s (a run's map history, for replay).
struct LandmarkMapSnapshot {
  double t_s = 0.0;
  LandmarkMap map;
};

}  // namespace slamkit
