#include "slamkit/eval/landmark_smoother.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// The unknowns: poses 1..n-1 (pose 0 is the gauge), then the landmarks in id order.
struct Layout {
  int poses = 0;
  std::map<LandmarkId, int> landmark_column;
  int PoseColumn(int pose) const { return pose == 0 ? -1 : 3 * (pose - 1); }
  int Size() const { return 3 * (poses - 1) + 2 * static_cast<int>(landmark_column.size()); }
};

// The normal equations H δ = b of one Gauss–Newton step, and the cost at the linearisation point.
struct NormalEquations {
  Triplets H;
  Eigen::VectorXd b;
  double chi2 = 0.0;
};

template <int R>
Eigen::Matrix<double, R, R> Information(const Eigen::Matrix<double, R, R>& covariance,
                                        const std::string& what) {
  const Eigen::LLT<Eigen::Matrix<double, R, R>> llt(covariance);
  if (!covariance.allFinite() || llt.info() != Eigen::Success) {
    throw std::invalid_argument("SmoothLandmarkSlam: " + what +
                                ": covariance not positive definite");
  }
  return llt.solve(Eigen::Matrix<double, R, R>::Identity());
}

// Adds rᵀ Ω r for a residual r whose Jacobian blocks J[i] act on the unknowns from column[i]
// (a column < 0 is held fixed and gets no equation).
template <int R, int N>
void AddResidual(const Eigen::Matrix<double, R, 1>& r, const Eigen::Matrix<double, R, R>& Omega,
                 const std::array<Eigen::Matrix<double, R, Eigen::Dynamic>, N>& J,
                 const std::array<int, N>& column, NormalEquations& eq) {
  eq.chi2 += r.dot(Omega * r);
  for (int i = 0; i < N; ++i) {
    if (column[i] < 0) continue;
    eq.b.segment(column[i], J[i].cols()) -= J[i].transpose() * Omega * r;
    for (int j = 0; j < N; ++j) {
      if (column[j] < 0) continue;
      const Eigen::MatrixXd block = J[i].transpose() * Omega * J[j];
      for (int a = 0; a < block.rows(); ++a) {
        for (int c = 0; c < block.cols(); ++c) {
          eq.H.emplace_back(column[i] + a, column[j] + c, block(a, c));
        }
      }
    }
  }
}

void AddOdometry(const SmootherOdometry& o, const std::vector<Pose2>& poses, const Layout& layout,
                 NormalEquations& eq) {
  Eigen::Matrix3d J_d_from, J_d_to;
  const Pose2 predicted = poses[o.from].Between(poses[o.to], &J_d_from, &J_d_to);
  Eigen::Vector3d r = predicted.vector() - o.delta.vector();
  r.z() = WrapAngle(r.z());
  const Eigen::Matrix3d Omega = Information<3>(o.covariance, "odometry " + std::to_string(o.from) +
                                                                 " -> " + std::to_string(o.to));
  AddResidual<3, 2>(r, Omega, {J_d_from, J_d_to},
                    {layout.PoseColumn(o.from), layout.PoseColumn(o.to)}, eq);
}

void AddSighting(const SmootherSighting& s, const std::vector<Pose2>& poses,
                 const std::map<LandmarkId, Eigen::Vector2d>& landmarks, const Layout& layout,
                 NormalEquations& eq) {
  Eigen::Matrix<double, 2, 3> J_z_pose;
  Eigen::Matrix2d J_z_landmark;
  const Eigen::Vector2d r =
      poses[s.pose].TransformTo(landmarks.at(s.landmark), &J_z_pose, &J_z_landmark) - s.z;
  const Eigen::Matrix2d Omega = Information<2>(s.covariance, "sighting of landmark " +
                                                                 std::to_string(s.landmark));
  AddResidual<2, 2>(r, Omega, {J_z_pose, J_z_landmark},
                    {layout.PoseColumn(s.pose), layout.landmark_column.at(s.landmark)}, eq);
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

LandmarkSmootherResult SmoothLandmarkSlam(std::span<const Pose2> initial_poses,
                                          std::span<const SmootherOdometry> odometry,
                                          std::span<const SmootherSighting> sightings,
                                          const LandmarkSmootherParams& params) {
  CheckInputs(initial_poses, odometry, sightings);
  LandmarkSmootherResult out;
  out.poses.assign(initial_poses.begin(), initial_poses.end());
  out.landmarks = InitialLandmarks(initial_poses, sightings);
  out.residuals = 3 * static_cast<int>(odometry.size()) + 2 * static_cast<int>(sightings.size());
  Layout layout;
  layout.poses = static_cast<int>(out.poses.size());
  for (const auto& [id, unused] : out.landmarks) {
    const int before = static_cast<int>(layout.landmark_column.size());
    layout.landmark_column[id] = 3 * (layout.poses - 1) + 2 * before;
  }
  const int size = layout.Size();
  out.converged = size == 0;
  for (out.iterations = 1; out.iterations <= params.max_iterations && size > 0; ++out.iterations) {
    NormalEquations eq;
    eq.b = Eigen::VectorXd::Zero(size);
    for (const SmootherOdometry& o : odometry) AddOdometry(o, out.poses, layout, eq);
    for (const SmootherSighting& s : sightings) {
      AddSighting(s, out.poses, out.landmarks, layout, eq);
    }
    Eigen::SparseMatrix<double> H(size, size);
    H.setFromTriplets(eq.H.begin(), eq.H.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(H);
    if (solver.info() != Eigen::Success || (solver.vectorD().array() <= 0.0).any()) {
      throw std::invalid_argument("SmoothLandmarkSlam: a pose or landmark is not constrained");
    }
    const Eigen::VectorXd delta = solver.solve(eq.b);
    for (int k = 1; k < layout.poses; ++k) {
      out.poses[k] = Pose2(out.poses[k].vector() + delta.segment<3>(layout.PoseColumn(k)));
    }
    for (auto& [id, p] : out.landmarks) p += delta.segment<2>(layout.landmark_column.at(id));
    out.chi2 = eq.chi2;
    if (delta.lpNorm<Eigen::Infinity>() < params.tolerance) {
      out.converged = true;
      break;
    }
  }
  out.iterations = std::min(out.iterations, params.max_iterations);
  return out;
}

}  // namespace slamkit
