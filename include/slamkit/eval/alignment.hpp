#pragma once

#include <span>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// The rigid motion T that best maps `from` onto `to` (least squares over corresponding pairs,
// Kabsch/Umeyama without scale), and the RMS distance that remains after applying it.
struct RigidAlignment {
  Pose2 transform;
  double rmse_m = 0.0;
};

RigidAlignment AlignPoints(std::span<const Eigen::Vector2d> from,
                           std::span<const Eigen::Vector2d> to);

}  // namespace slamkit
