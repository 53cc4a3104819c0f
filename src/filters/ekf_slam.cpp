#include "slamkit/filters/ekf_slam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <tbb/parallel_for.h>

namespace slamkit {
namespace {

void CheckFinite(const PointObservation& obs) {
  if (!obs.z.allFinite() || !obs.R.allFinite()) {
    throw std::invalid_argument("EkfSlam::Update: observation with a non-finite value");
  }
}

}  // namespace

EkfSlam::EkfSlam(const EkfSlamParams& params, std::unique_ptr<MotionModel> motion,
                 std::unique_ptr<PointSensorModel> sensor)
    : params_(params),
      motion_(std::move(motion)),
      sensor_(std::move(sensor)),
      associator_(params.association) {
  Reset(Pose2());
}

void EkfSlam::Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) {
  const int capacity = 3 + 2 * std::max(params_.initial_landmark_capacity, 1);
  x_ = Eigen::VectorXd::Zero(capacity);
  P_ = Eigen::MatrixXd::Zero(capacity, capacity);
  U_ = Eigen::MatrixXd::Zero(capacity, 8);
  pose_cols_ = Eigen::MatrixXd::Zero(capacity, 3);
  m_ = 0;
  n_ = 3;
  x_.head<3>() = pose.vector();
  P_.topLeftCorner<3, 3>() = pose_cov;
  source_ids_.clear();
  index_of_id_.clear();
}

void EkfSlam::Reserve(int state_size) {
  const int capacity = static_cast<int>(x_.size());
  if (state_size <= capacity) return;
  ApplyDeferredDowndate();  // growth is rare (doubling): simpler than carrying U over
  const int grown = std::max(state_size, 2 * capacity);
  U_ = Eigen::MatrixXd::Zero(grown, U_.cols());
  pose_cols_ = Eigen::MatrixXd::Zero(grown, 3);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(grown);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(grown, grown);
  x.head(n_) = x_.head(n_);
  P.topLeftCorner(n_, n_).triangularView<Eigen::Upper>() = P_.topLeftCorner(n_, n_);
  x_.swap(x);
  P_.swap(P);
}

// SPEC S2, Eq. 2 (Probabilistic Robotics Table 10.1): only the pose rows of the covariance move.
void EkfSlam::Predict(const Control& u, double dt_s, const ControlCovariance* control_noise) {
  Eigen::Matrix3d F;
  ControlJacobian G;
  const Pose2 moved = motion_->Move(pose(), u, dt_s, &F, &G);
  const ControlCovariance Q = control_noise ? *control_noise : motion_->Noise(u, dt_s);
  const Eigen::Matrix3d P_vv = P_.topLeftCorner<3, 3>().selfadjointView<Eigen::Upper>();
  P_.topLeftCorner<3, 3>() = F * P_vv * F.transpose() + G * Q * G.transpose();
  if (n_ > 3) {
    // Row block: P_vm lives in rows 0-2 of the stored upper triangle.
    auto P_vm = P_.block(0, 3, 3, n_ - 3);
    P_vm = (F * P_vm).eval();
  }
  x_.head<3>() = moved.vector();
}

Eigen::MatrixXd EkfSlam::CurrentColumns(int c, int k) const {
  Eigen::MatrixXd cols(n_, k);
  cols.topRows(c) = P_.block(0, c, c, k);
  cols.middleRows(c, k) = P_.block(c, c, k, k).selfadjointView<Eigen::Upper>();
  const int below = n_ - c - k;
  cols.bottomRows(below) = P_.block(c, c + k, k, below).transpose();
  if (m_ > 0) {
    // Column by column (axpy over n): a GEMM call would repack all of U for these k columns.
    for (int j = 0; j < m_; ++j) {
      const auto u = U_.col(j).head(n_);
      for (int q = 0; q < k; ++q) cols.col(q) -= U_(c + q, j) * u;
    }
  }
  return cols;
}

Eigen::MatrixXd EkfSlam::CurrentPoseColumns() const {
  return m_ > 0 ? Eigen::MatrixXd(pose_cols_.topRows(n_)) : CurrentColumns(0, 3);
}

// Blocks read here lie on or above the diagonal (r <= c), where the stored triangle is valid.
template <int R, int C>
Eigen::Matrix<double, R, C> EkfSlam::CurrentBlock(int r, int c) const {
  Eigen::Matrix<double, R, C> block = P_.block<R, C>(r, c);
  if constexpr (R == C) {
    if (r == c) block = P_.block<R, C>(r, c).template selfadjointView<Eigen::Upper>();
  }
  if (m_ > 0) {
    block.noalias() -= U_.block(r, 0, R, m_) * U_.block(c, 0, C, m_).transpose();
  }
  return block;
}

void EkfSlam::ApplyDeferredDowndate() {
  if (m_ == 0) return;
  // Fixed blocks, whatever the thread count, so the sums and hence the bits never change.
  constexpr int kBlock = 128;
  const auto U = U_.topLeftCorner(n_, m_);
  const int blocks = (n_ + kBlock - 1) / kBlock;
  tbb::parallel_for(0, blocks, [&](int b) {
    const int j0 = b * kBlock, w = std::min(kBlock, n_ - j0);
    const auto U_j = U.middleRows(j0, w);
    P_.block(0, j0, j0, w).noalias() -= U.topRows(j0) * U_j.transpose();
    P_.block(j0, j0, w, w).triangularView<Eigen::Upper>() -= U_j * U_j.transpose();
  });
  m_ = 0;
}

Eigen::Matrix2d EkfSlam::InnovationCovariance(int landmark, const Eigen::Matrix<double, 2, 3>& H_x,
                                              const Eigen::Matrix2d& H_l,
                                              const Eigen::Matrix2d& R) const {
  const int c = Offset(landmark);
  const Eigen::Matrix3d P_vv = CurrentBlock<3, 3>(0, 0);
  const Eigen::Matrix<double, 3, 2> P_vl = CurrentBlock<3, 2>(0, c);
  const Eigen::Matrix2d P_ll = CurrentBlock<2, 2>(c, c);
  const Eigen::Matrix2d cross = H_x * P_vl * H_l.transpose();
  return H_x * P_vv * H_x.transpose() + cross + cross.transpose() +
         H_l * P_ll * H_l.transpose() + R;
}

double EkfSlam::MahalanobisDistance(int landmark, const PointObservation& obs) const {
  Eigen::Matrix<double, 2, 3> H_x;
  Eigen::Matrix2d H_l;
  const Eigen::Vector2d z_pred = sensor_->Predict(pose(), LandmarkPosition(landmark), &H_x, &H_l);
  const Eigen::Vector2d nu = sensor_->Innovation(obs.z, z_pred);
  const Eigen::Matrix2d S = InnovationCovariance(landmark, H_x, H_l, obs.R);
  return nu.dot(S.llt().solve(nu));
}

// SPEC S1 item 1 (Probabilistic Robotics Table 10.2, one innovation at a time). H is zero except
// for the pose and this landmark's columns, so P Hᵀ costs O(n) and the covariance update is the
// symmetric rank-2 downdate P ← P − (P Hᵀ L⁻ᵀ)(P Hᵀ L⁻ᵀ)ᵀ with S = L Lᵀ, O(n²) on one triangle.
void EkfSlam::UpdateLandmarkDeferred(int landmark, const PointObservation& obs) {
  const int c = Offset(landmark);
  Eigen::Matrix<double, 2, 3> H_x;
  Eigen::Matrix2d H_l;
  const Eigen::Vector2d z_pred = sensor_->Predict(pose(), LandmarkPosition(landmark), &H_x, &H_l);
  const Eigen::Vector2d nu = sensor_->Innovation(obs.z, z_pred);

  const Eigen::MatrixXd P_x = CurrentPoseColumns();
  const Eigen::Matrix<double, Eigen::Dynamic, 2> PHt =
      P_x * H_x.transpose() + CurrentColumns(c, 2) * H_l.transpose();
  const Eigen::Matrix2d S = H_x * PHt.topRows<3>() + H_l * PHt.middleRows<2>(c) + obs.R;
  const Eigen::LLT<Eigen::Matrix2d> llt(S);
  if (llt.info() != Eigen::Success) return;  // S is never singular for R > 0; guard anyway
  // V = P Hᵀ L⁻ᵀ, so K ν = V L⁻¹ ν and K S Kᵀ = V Vᵀ.
  const Eigen::Matrix2d L_inv_t =
      llt.matrixL().solve(Eigen::Matrix2d::Identity()).transpose();
  if (m_ + 2 > U_.cols()) U_.conservativeResize(Eigen::NoChange, 2 * U_.cols());
  auto V = U_.block(0, m_, n_, 2);
  V.noalias() = PHt * L_inv_t;
  x_.head(n_) += V * (L_inv_t.transpose() * nu);
  x_[2] = WrapAngle(x_[2]);
  // Every observation needs the pose columns: keep them current in O(n) rather than correcting
  // them through all of U each time.
  if (m_ == 0) pose_cols_.topRows(n_) = P_x;
  pose_cols_.topRows(n_).noalias() -= V * V.topRows<3>().transpose();
  m_ += 2;
}

// SPEC S2, Eq. 8: the new landmark's mean from the inverse model; its covariance and cross terms
// from the inverse model's Jacobians, G_x P_v· and G_x P_vv G_xᵀ + G_z R G_zᵀ.
int EkfSlam::AddLandmark(const PointObservation& obs) {
  Eigen::Matrix<double, 2, 3> G_x;
  Eigen::Matrix2d G_z;
  const Eigen::Vector2d l = sensor_->Invert(pose(), obs.z, &G_x, &G_z);
  Reserve(n_ + 2);
  const Eigen::MatrixXd P_xv = CurrentPoseColumns();  // n×3
  const Eigen::Matrix3d P_vv = P_xv.topRows<3>();
  // The stored block holds the current cross-covariance and the new rows of U are zero, so the
  // deferred correction leaves it untouched.
  P_.block(0, n_, n_, 2) = P_xv * G_x.transpose();
  P_.block<2, 2>(n_, n_) = G_x * P_vv * G_x.transpose() + G_z * obs.R * G_z.transpose();
  U_.block(n_, 0, 2, m_).setZero();
  pose_cols_.block<2, 3>(n_, 0) = G_x * P_vv;
  x_.segment<2>(n_) = l;
  n_ += 2;
  const int index = NumLandmarks();
  source_ids_.push_back(obs.id);
  if (obs.id != kNoLandmark) index_of_id_.emplace(obs.id, index);
  return index;
}

AssociationDecision EkfSlam::AssociateKnown(const PointObservation& obs) const {
  AssociationDecision d;
  const auto it = index_of_id_.find(obs.id);
  if (it == index_of_id_.end()) {
    d.kind = AssociationDecision::Kind::kNew;
    d.distance_chi2 = std::numeric_limits<double>::infinity();
  } else {
    d.kind = AssociationDecision::Kind::kMatched;
    d.landmark = it->second;
    d.distance_chi2 = MahalanobisDistance(it->second, obs);
  }
  return d;
}

AssociationDecision EkfSlam::AssociateNearest(const PointObservation& obs,
                                              const std::vector<char>& used) const {
  const Eigen::Vector2d position = pose().translation();
  const double reach = sensor_->MaxRange() + params_.association_margin_m;
  candidates_.clear();
  for (int i = 0; i < NumLandmarks(); ++i) {
    if (used[i]) continue;
    if ((LandmarkPosition(i) - position).squaredNorm() > reach * reach) continue;
    candidates_.push_back({i, MahalanobisDistance(i, obs)});
  }
  return associator_.Associate(candidates_);
}

std::vector<AssociationDecision> EkfSlam::Update(std::span<const PointObservation> observations) {
  std::vector<AssociationDecision> decisions;
  decisions.reserve(observations.size());
  // A landmark takes at most one sighting per scan: two sightings are two landmarks.
  std::vector<char> used(NumLandmarks() + observations.size(), 0);
  for (const PointObservation& obs : observations) {
    CheckFinite(obs);
    AssociationDecision d = params_.known_association ? AssociateKnown(obs)
                                                      : AssociateNearest(obs, used);
    if (d.kind == AssociationDecision::Kind::kMatched) {
      UpdateLandmarkDeferred(d.landmark, obs);
    } else if (d.kind == AssociationDecision::Kind::kNew) {
      d.landmark = AddLandmark(obs);
    }
    if (d.landmark >= 0) used[d.landmark] = 1;
    decisions.push_back(d);
  }
  ApplyDeferredDowndate();
  return decisions;
}

Eigen::Matrix3d EkfSlam::PoseCovariance() const {
  return P_.topLeftCorner<3, 3>().selfadjointView<Eigen::Upper>();
}

Eigen::Matrix2d EkfSlam::LandmarkCovariance(int landmark) const {
  const int c = Offset(landmark);
  return P_.block<2, 2>(c, c).selfadjointView<Eigen::Upper>();
}

LandmarkMap EkfSlam::Map() const {
  LandmarkMap map;
  map.landmarks.reserve(NumLandmarks());
  for (int i = 0; i < NumLandmarks(); ++i) {
    map.landmarks.push_back({source_ids_[i], LandmarkPosition(i), LandmarkCovariance(i)});
  }
  return map;
}

Eigen::MatrixXd EkfSlam::Covariance() const {
  return P_.topLeftCorner(n_, n_).selfadjointView<Eigen::Upper>();
}

}  // namespace slamkit
