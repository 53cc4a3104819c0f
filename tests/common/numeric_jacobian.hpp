#pragma once

#include <Eigen/Core>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"

namespace slamkit::testing {

// Central-difference Jacobian of f: R^n -> R^m at x. Output component `angle_row` (if >= 0) is an
// angle: its differences are wrapped so that outputs near ±π differentiate correctly.
template <typename F>
Eigen::MatrixXd NumericJacobian(F f, const Eigen::VectorXd& x, int angle_row = -1,
                                double h = 1e-6) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    Eigen::VectorXd d = f(xp) - f(xm);
    if (angle_row >= 0) d[angle_row] = WrapAngle(d[angle_row]);
    J.col(i) = d / (2.0 * h);
  }
  return J;
}

inline Pose2 RandomPose(Rng& rng, double extent_m = 10.0) {
  return {rng.Uniform(-extent_m, extent_m), rng.Uniform(-extent_m, extent_m),
          rng.Uniform(-3.14159, 3.14159)};
}

inline Eigen::Vector2d RandomPointNear(const Pose2& x, Rng& rng, double min_m = 1.0,
                                       double max_m = 20.0) {
  const double r = rng.Uniform(min_m, max_m);
  const double a = rng.Uniform(-3.14159, 3.14159);
  return x.translation() + r * Eigen::Vector2d(std::cos(a), std::sin(a));
}

}  // namespace slamkit::testing
