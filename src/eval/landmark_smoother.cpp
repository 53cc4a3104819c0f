#include "slamkit/eval/landmark_smoother.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <ceres/problem.h>
#include <ceres/solver.h>

#include "slamkit/optim/landmark_factors.hpp"

namespace slamkit {
namespace {

// The factor, or the input's own message for a covariance that is not positive definite.
template <class Factor, class... Args>
Factor* MakeFactor(const std::string& what, const Args&... args) {
  try {
    return new Factor(args...);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("SmoothLandmarkSlam: " + what +
                                ": covariance not positive definite");
  }
}

// Each landmark at the mean of its sightings from the initial poses.
std::map<LandmarkId, Eigen::Vector2d> InitialLandmarks(
    std::span<const Pose2> poses, std::span<const SmootherSighting> sightings) {
  std::map<LandmarkId, std::pair<Eigen::Vector2d, int>> sum;
  for (const SmootherSighting& s : sightings) {
    auto& [p, n] = sum.try_emplace(s.landmark, Eigen::Vector2d::Zero(), 0).first->second;
    p += poses[s.pose].TransformFrom(s.z);
    ++n;
  }
  std::map<LandmarkId, Eigen::Vector2d> out;
  for (const auto& [id, pn] : sum) out[id] = pn.first / pn.second;
  return out;
}

void CheckInputs(std::span<const Pose2> poses, std::span<const SmootherOdometry> odometry,
                 std::span<const SmootherSighting> sightings) {
  const int n = static_cast<int>(poses.size());
  if (n == 0) throw std::invalid_argument("SmoothLandmarkSlam: no poses");
  std::vector<bool> constrained(poses.size(), false);
  constrained[0] = true;
  auto check = [&](int k, const std::string& what) {
    if (k < 0 || k >= n) {
      throw std::invalid_argument("SmoothLandmarkSlam: " + what + " names pose " +
                                  std::to_string(k) + " of " + std::to_string(n));
    }
  };
  for (const SmootherOdometry& o : odometry) {
    check(o.from, "odometry");
    check(o.to, "odometry");
    constrained[o.from] = constrained[o.to] = true;
  }
  for (const SmootherSighting& s : sightings) check(s.pose, "a sighting");
  for (int k = 0; k < n; ++k) {
    if (!constrained[k]) {
      throw std::invalid_argument("SmoothLandmarkSlam: no odometry constrains pose " +
                                  std::to_string(k));
    }
  }
}

}  // namespace

// Levenberg-Marquardt on Ceres (optim's factors), sparse normal Cholesky: the same optimum as
// the Gauss-Newton of Square Root SAM from a start near it.
LandmarkSmootherResult SmoothLandmarkSlam(std::span<const Pose2> initial_poses,
                                          std::span<const SmootherOdometry> odometry,
                                          std::span<const SmootherSighting> sightings,
                                          const LandmarkSmootherParams& params) {
  CheckInputs(initial_poses, odometry, sightings);
  LandmarkSmootherResult out;
  out.residuals = 3 * static_cast<int>(odometry.size()) + 2 * static_cast<int>(sightings.size());
  std::vector<Eigen::Vector3d> x;
  for (const Pose2& p : initial_poses) x.push_back(p.vector());
  std::map<LandmarkId, Eigen::Vector2d> landmarks = InitialLandmarks(initial_poses, sightings);
  ceres::Problem problem;
  for (const SmootherOdometry& o : odometry) {
    problem.AddResidualBlock(
        MakeFactor<OdometryDeltaFactor>(
            "odometry " + std::to_string(o.from) + " -> " + std::to_string(o.to), o.delta,
            o.covariance),
        nullptr, x[o.from].data(), x[o.to].data());
  }
  for (const SmootherSighting& s : sightings) {
    problem.AddResidualBlock(
        MakeFactor<PosePointFactor>("sighting of landmark " + std::to_string(s.landmark), s.z,
                                    s.covariance),
        nullptr, x[s.pose].data(), landmarks.at(s.landmark).data());
  }
  problem.SetParameterBlockConstant(x[0].data());  // the gauge
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = params.max_iterations;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = params.tolerance * 1e-6;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (summary.termination_type == ceres::FAILURE) {
    throw std::invalid_argument("SmoothLandmarkSlam: a pose or landmark is not constrained (" +
                                summary.message + ")");
  }
  for (const Eigen::Vector3d& v : x) out.poses.emplace_back(v);
  out.landmarks = std::move(landmarks);
  out.chi2 = 2.0 * summary.final_cost;  // Ceres' cost is half the sum of squares
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  return out;
}

}  // namespace slamkit
