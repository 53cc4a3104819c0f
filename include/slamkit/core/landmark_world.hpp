#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"

namespace slamkit {

// A true point landmark of a world or a data set.
struct Landmark {
  LandmarkId id = kNoLandmark;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
};

// A world of point landmarks with unique ids.
struct LandmarkWorld {
  std::vector<Landmark> landmarks;
};

}  // namespace slamkit
