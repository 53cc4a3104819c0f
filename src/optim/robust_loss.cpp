#include "slamkit/optim/robust_loss.hpp"

#include <cmath>
#include <stdexcept>

namespace slamkit {

DcsLoss::DcsLoss(double phi) : phi_(phi) {
  if (!(phi > 0.0 && std::isfinite(phi))) throw std::invalid_argument("DCS: phi must be > 0");
}

void DcsLoss::Evaluate(double s, double rho[3]) const {
  if (s <= phi_) {
    rho[0] = s;
    rho[1] = 1.0;
    rho[2] = 0.0;
    return;
  }
  const double d = s + phi_;
  rho[0] = phi_ * (3.0 * s - phi_) / d;
  rho[1] = 4.0 * phi_ * phi_ / (d * d);
  rho[2] = -8.0 * phi_ * phi_ / (d * d * d);
}

std::unique_ptr<ceres::LossFunction> MakeRobustLoss(const RobustLossParams& p) {
  if (p.kind == RobustLossKind::kNone) return nullptr;
  if (!(p.scale > 0.0 && std::isfinite(p.scale))) {
    throw std::invalid_argument("robust loss: the scale must be positive and finite");
  }
  switch (p.kind) {
    case RobustLossKind::kHuber: return std::make_unique<ceres::HuberLoss>(p.scale);
    case RobustLossKind::kCauchy: return std::make_unique<ceres::CauchyLoss>(p.scale);
    case RobustLossKind::kDcs: return std::make_unique<DcsLoss>(p.scale);
    case RobustLossKind::kNone: break;
  }
  return nullptr;
}

std::string_view RobustLossName(RobustLossKind kind) {
  switch (kind) {
    case RobustLossKind::kHuber: return "huber";
    case RobustLossKind::kCauchy: return "cauchy";
    case RobustLossKind::kDcs: return "dcs";
    case RobustLossKind::kNone: break;
  }
  return "none";
}

}  // namespace slamkit
