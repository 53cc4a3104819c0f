#pragma once

#include <vector>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

struct StampedPose {
  double t_s = 0.0;
  Pose2 pose;
};

using Trajectory = std::vector<StampedPose>;

}  // namespace slamkit
