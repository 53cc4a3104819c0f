#include "slamkit/models/vehicle.hpp"

namespace slamkit {

std::unique_ptr<MotionModel> MakeMotionModel(const VehicleParams& params) {
  switch (params.kind) {
    case MotionKind::kUnicycle:
      return std::make_unique<UnicycleModel>(params.unicycle);
    case MotionKind::kCarLike:
      return std::make_unique<CarLikeModel>(params.car_like);
    case MotionKind::kOdometry:
      return std::make_unique<OdometryModel>(params.odometry);
  }
  return nullptr;
}

std::string_view ToString(MotionKind kind) {
  switch (kind) {
    case MotionKind::kUnicycle:
      return "unicycle";
    case MotionKind::kCarLike:
      return "car_like";
    case MotionKind::kOdometry:
      return "odometry";
  }
  return "?";
}

}  // namespace slamkit
