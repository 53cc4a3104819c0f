// BlockEkf's sequential update, dispatched on the innovation's dimension and the dimensions
// of the blocks it observes (each pairing is its own instantiation: this unit and the
// covariance's are compiled apart so that they build side by side).

#include <Eigen/Cholesky>
#include <algorithm>

#include "block_dispatch.hpp"
#include "compressed_area.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

using internal::WithDim;
using internal::WithDims;
using internal::WithMeasurementDim;

namespace {
template <int kZ>
constexpr bool kFixedZ = kZ != Eigen::Dynamic;
}  // namespace

// P Hᵀ (n × kZ): H is zero outside the observed blocks, so each costs O(n). Two blocks (pose and
// landmark, two poses) are summed in one expression, the form the point-landmark filter has
// always used, so that its results stay bit for bit the same.
template <int kZ>
TallMatrix<kZ> BlockEkf::CovarianceTimesHt(
    const Linearisation& obs) const {
  const std::span<const BlockJacobian> H = obs.H.view();
  TallMatrix<kZ> PHt;
  if (H.size() == 2) {
    Eigen::MatrixXd scratch_0, scratch_1;
    const Eigen::Ref<const Eigen::MatrixXd> P_0 = BlockColumns(H[0].block, scratch_0);
    const Eigen::Ref<const Eigen::MatrixXd> P_1 = BlockColumns(H[1].block, scratch_1);
    WithDims<kFixedZ<kZ>>(BlockDim(H[0].block), BlockDim(H[1].block), [&](auto D0, auto D1) {
      const SmallMatrix<kZ, decltype(D0)::value> J_0 = H[0].J;
      const SmallMatrix<kZ, decltype(D1)::value> J_1 = H[1].J;
      PHt = P_0 * J_0.transpose() + P_1 * J_1.transpose();
    });
    return PHt;
  }
  PHt.setZero(n_, obs.innovation.size());
  for (const BlockJacobian& h : H) {
    Eigen::MatrixXd scratch;
    const Eigen::Ref<const Eigen::MatrixXd> P_b = BlockColumns(h.block, scratch);
    WithDim<kFixedZ<kZ>>(BlockDim(h.block), [&](auto D) {
      const SmallMatrix<kZ, decltype(D)::value> J = h.J;
      PHt += P_b * J.transpose();
    });
  }
  return PHt;
}

// S = H (P Hᵀ) + R, reusing the P Hᵀ the update computed anyway.
template <int kZ>
SmallMatrix<kZ, kZ> BlockEkf::InnovationCovarianceFromPHt(
    const Linearisation& obs, const TallMatrix<kZ>& PHt) const {
  const std::span<const BlockJacobian> H = obs.H.view();
  const SmallMatrix<kZ, kZ> R = obs.R;
  SmallMatrix<kZ, kZ> S;
  if (H.size() == 2) {
    WithDims<kFixedZ<kZ>>(BlockDim(H[0].block), BlockDim(H[1].block), [&](auto D0, auto D1) {
      constexpr int kD0 = decltype(D0)::value, kD1 = decltype(D1)::value;
      const SmallMatrix<kZ, kD0> J_0 = H[0].J;
      const SmallMatrix<kZ, kD1> J_1 = H[1].J;
      S = J_0 * PHt.template middleRows<kD0>(BlockOffset(H[0].block), BlockDim(H[0].block)) +
          J_1 * PHt.template middleRows<kD1>(BlockOffset(H[1].block), BlockDim(H[1].block)) + R;
    });
    return S;
  }
  S = R;
  for (const BlockJacobian& h : H) {
    WithDim<kFixedZ<kZ>>(BlockDim(h.block), [&](auto D) {
      constexpr int kD = decltype(D)::value;
      const SmallMatrix<kZ, kD> J = h.J;
      S += J * PHt.template middleRows<kD>(BlockOffset(h.block), BlockDim(h.block));
    });
  }
  return S;
}

// SPEC S1 item 1 (Probabilistic Robotics Table 10.2, one innovation at a time). With S = L Lᵀ
// the covariance update is the symmetric rank-kZ downdate P ← P − V Vᵀ, V = P Hᵀ L⁻ᵀ, and the
// mean moves by K ν = V L⁻¹ ν; V joins the deferred factor U.
template <int kZ>
bool BlockEkf::UpdateFixed(const Linearisation& obs) {
  using MatrixZ = SmallMatrix<kZ, kZ>;
  if (m_ == 0) StartPoseCache();
  const TallMatrix<kZ> PHt = CovarianceTimesHt<kZ>(obs);
  const MatrixZ S = InnovationCovarianceFromPHt<kZ>(obs, PHt);
  const Eigen::LLT<MatrixZ> llt(S);
  if (llt.info() != Eigen::Success) return false;  // never for R > 0; guard anyway
  const int z = static_cast<int>(obs.innovation.size());
  const MatrixZ L_inv_t = llt.matrixL().solve(MatrixZ::Identity(z, z)).transpose();
  if (m_ + z > U_.cols()) U_.conservativeResize(Eigen::NoChange, std::max<Eigen::Index>(2 * U_.cols(), m_ + z));
  auto V = U_.block(0, m_, n_, z);
  V.noalias() = PHt * L_inv_t;
  const SmallMatrix<kZ, 1> nu = obs.innovation;
  x_.head(n_) += V * (L_inv_t.transpose() * nu);
  WrapAngles();
  // Nearly every observation reads pose columns: keep them current in O(n) rather than
  // correcting them through all of U each time.
  for (const int p : pose_blocks_) {
    pose_cols_.block(0, 3 * pose_slot_[p], n_, 3).noalias() -=
        V * V.template middleRows<3>(BlockOffset(p)).transpose();
  }
  m_ += z;
  return true;
}

bool BlockEkf::Update(const Linearisation& obs) {
  if (area_) {
    if (const std::optional<Linearisation> local = ToArea(obs)) return area_->local.Update(*local);
    Synchronise();
  }
  return WithMeasurementDim(static_cast<int>(obs.innovation.size()),
                            [&](auto Z) { return UpdateFixed<decltype(Z)::value>(obs); });
}

}  // namespace slamkit
