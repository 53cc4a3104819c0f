#pragma once

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// One relation of Kümmerle et al. 2009: the pose at t2_s expressed in the frame of the pose at
// t1_s.
struct PoseRelation {
  double t1_s = 0.0;
  double t2_s = 0.0;
  Pose2 delta;
};

}  // namespace slamkit
