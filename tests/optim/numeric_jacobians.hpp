// Checks a ceres::CostFunction's analytic Jacobians against central differences (optim tests).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <ceres/cost_function.h>
#include <gtest/gtest.h>

namespace slamkit::optim_test {

// The analytic Jacobians of every parameter block against central differences.
inline void ExpectGradientsMatch(const ceres::CostFunction& f, std::vector<double*> parameters) {
  const int m = f.num_residuals();
  const std::vector<int32_t>& sizes = f.parameter_block_sizes();
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J;
  std::vector<double*> jacobians;
  for (const int32_t n : sizes) J.emplace_back(m, n);
  for (auto& j : J) jacobians.push_back(j.data());
  Eigen::VectorXd r(m), plus(m), minus(m);
  ASSERT_TRUE(f.Evaluate(parameters.data(), r.data(), jacobians.data()));
  for (std::size_t b = 0; b < sizes.size(); ++b) {
    for (int k = 0; k < sizes[b]; ++k) {
      const double keep = parameters[b][k], h = 1e-6;
      parameters[b][k] = keep + h;
      f.Evaluate(parameters.data(), plus.data(), nullptr);
      parameters[b][k] = keep - h;
      f.Evaluate(parameters.data(), minus.data(), nullptr);
      parameters[b][k] = keep;
      const Eigen::VectorXd numeric = (plus - minus) / (2 * h);
      EXPECT_LT((J[b].col(k) - numeric).norm(), 1e-6 * (1 + numeric.norm())) << b << ", " << k;
    }
  }
}

}  // namespace slamkit::optim_test
