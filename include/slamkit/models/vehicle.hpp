#pragma once

#include <memory>
#include <string_view>

#include "slamkit/models/car_like.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/unicycle.hpp"

namespace slamkit {

enum class MotionKind { kUnicycle, kCarLike, kOdometry };

// Which motion model a vehicle uses, with the parameters of each kind (only the chosen one is read).
struct VehicleParams {
  MotionKind kind = MotionKind::kCarLike;
  UnicycleParams unicycle;
  CarLikeParams car_like;
  OdometryParams odometry;
};

std::unique_ptr<MotionModel> MakeMotionModel(const VehicleParams& params);
std::string_view ToString(MotionKind kind);

}  // namespace slamkit
