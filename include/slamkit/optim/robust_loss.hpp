#pragma once

#include <memory>
#include <string_view>

#include <ceres/loss_function.h>

namespace slamkit {

// Robust losses ρ(s) of a factor's squared whitened residual s = |r|², for loop closures that
// may be false: past `scale` they grow slower than s, so one wrong closure cannot tear a graph.
enum class RobustLossKind {
  kNone,    // ρ(s) = s
  kHuber,   // ceres::HuberLoss(scale): quadratic up to |r| = scale, linear beyond
  kCauchy,  // ceres::CauchyLoss(scale): scale² log(1 + s / scale²)
  kDcs,     // Dynamic Covariance Scaling (Agarwal et al., ICRA 2013): DcsLoss(Φ = scale)
};

struct RobustLossParams {
  RobustLossKind kind = RobustLossKind::kNone;
  double scale = 1.0;  // Huber's and Cauchy's |r| knee; DCS's Φ in units of s
};

// Nullptr for kNone (Ceres' plain squared loss); throws std::invalid_argument for a scale that is
// not positive and finite.
std::unique_ptr<ceres::LossFunction> MakeRobustLoss(const RobustLossParams& params);

std::string_view RobustLossName(RobustLossKind kind);

// DCS as a loss: a residual is scaled by min(1, 2Φ / (Φ + s)), so its cost is ρ(s) = s for
// s <= Φ and Φ (3 s − Φ) / (s + Φ) beyond (ρ' = (2Φ / (Φ + s))², the scaling squared; ρ tends to
// 3Φ, so a closure can cost at most three times the knee).
class DcsLoss final : public ceres::LossFunction {
 public:
  explicit DcsLoss(double phi);
  void Evaluate(double s, double rho[3]) const override;

 private:
  double phi_;
};

}  // namespace slamkit
