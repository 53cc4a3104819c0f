// The parts of BlockEkf whose small matrices take fixed sizes: the sequential update, the
// innovation covariance and augmentation, each dispatched on the dimensions involved.

#include <tbb/parallel_for.h>

#include <Eigen/Cholesky>

#include "block_dispatch.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

using internal::WithDim;
using internal::WithDims;

template <int R, int C>
Eigen::Matrix<double, R, C> BlockEkf::CurrentBlock(int r, int c) const {
  Eigen::Matrix<double, R, C> block = P_.block<R, C>(r, c);
  if constexpr (R == C) {
    if (r == c) block = P_.block<R, C>(r, c).template selfadjointView<Eigen::Upper>();
  }
  if (m_ > 0) {
    block.noalias() -= U_.block(r, 0, R, m_) * U_.block(c, 0, C, m_).transpose();
  }
  return block;
}

// Block (a, b) of the current covariance; the stored triangle holds whichever lies above.
template <int R, int C>
Eigen::Matrix<double, R, C> BlockEkf::CurrentBlockOf(int a, int b) const {
  const int r = blocks_[a].offset, c = blocks_[b].offset;
  if (r <= c) return CurrentBlock<R, C>(r, c);
  return CurrentBlock<C, R>(c, r).transpose();
}

Eigen::MatrixXd BlockEkf::CovarianceBlock(int a, int b) const {
  return WithDim(BlockDim(a), [&](auto R) {
    return WithDim(BlockDim(b), [&](auto C) -> Eigen::MatrixXd {
      return CurrentBlockOf<decltype(R)::value, decltype(C)::value>(a, b);
    });
  });
}

void BlockEkf::ApplyPendingDowndate() {
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
  NormaliseBlocks();
}

// P Hᵀ (n × kZ): H is zero outside the observed blocks, so each costs O(n). Two blocks (pose and
// landmark, two poses) are summed in one expression, the form the point-landmark filter has
// always used, so that its results stay bit for bit the same.
template <int kZ>
Eigen::Matrix<double, Eigen::Dynamic, kZ> BlockEkf::CovarianceTimesHt(
    const Linearisation& obs) const {
  const std::span<const BlockJacobian> H = obs.H.view();
  Eigen::Matrix<double, Eigen::Dynamic, kZ> PHt;
  if (H.size() == 2) {
    Eigen::MatrixXd scratch_0, scratch_1;
    const Eigen::Ref<const Eigen::MatrixXd> P_0 = BlockColumns(H[0].block, scratch_0);
    const Eigen::Ref<const Eigen::MatrixXd> P_1 = BlockColumns(H[1].block, scratch_1);
    WithDims(BlockDim(H[0].block), BlockDim(H[1].block), [&](auto D0, auto D1) {
      const Eigen::Matrix<double, kZ, decltype(D0)::value> J_0 = H[0].J;
      const Eigen::Matrix<double, kZ, decltype(D1)::value> J_1 = H[1].J;
      PHt = P_0 * J_0.transpose() + P_1 * J_1.transpose();
    });
    return PHt;
  }
  PHt.setZero(n_, kZ);
  for (const BlockJacobian& h : H) {
    Eigen::MatrixXd scratch;
    const Eigen::Ref<const Eigen::MatrixXd> P_b = BlockColumns(h.block, scratch);
    WithDim(BlockDim(h.block), [&](auto D) {
      const Eigen::Matrix<double, kZ, decltype(D)::value> J = h.J;
      PHt += P_b * J.transpose();
    });
  }
  return PHt;
}

// S = H (P Hᵀ) + R, reusing the P Hᵀ the update computed anyway.
template <int kZ>
Eigen::Matrix<double, kZ, kZ> BlockEkf::InnovationCovarianceFromPHt(
    const Linearisation& obs, const Eigen::Matrix<double, Eigen::Dynamic, kZ>& PHt) const {
  const std::span<const BlockJacobian> H = obs.H.view();
  const Eigen::Matrix<double, kZ, kZ> R = obs.R;
  Eigen::Matrix<double, kZ, kZ> S;
  if (H.size() == 2) {
    WithDims(BlockDim(H[0].block), BlockDim(H[1].block), [&](auto D0, auto D1) {
      constexpr int kD0 = decltype(D0)::value, kD1 = decltype(D1)::value;
      const Eigen::Matrix<double, kZ, kD0> J_0 = H[0].J;
      const Eigen::Matrix<double, kZ, kD1> J_1 = H[1].J;
      S = J_0 * PHt.template middleRows<kD0>(BlockOffset(H[0].block)) +
          J_1 * PHt.template middleRows<kD1>(BlockOffset(H[1].block)) + R;
    });
    return S;
  }
  S = R;
  for (const BlockJacobian& h : H) {
    WithDim(BlockDim(h.block), [&](auto D) {
      constexpr int kD = decltype(D)::value;
      const Eigen::Matrix<double, kZ, kD> J = h.J;
      S += J * PHt.template middleRows<kD>(BlockOffset(h.block));
    });
  }
  return S;
}

// SPEC S1 item 1 (Probabilistic Robotics Table 10.2, one innovation at a time). With S = L Lᵀ
// the covariance update is the symmetric rank-kZ downdate P ← P − V Vᵀ, V = P Hᵀ L⁻ᵀ, and the
// mean moves by K ν = V L⁻¹ ν; V joins the deferred factor U.
template <int kZ>
bool BlockEkf::UpdateFixed(const Linearisation& obs) {
  using MatrixZ = Eigen::Matrix<double, kZ, kZ>;
  if (m_ == 0) StartPoseCache();
  const Eigen::Matrix<double, Eigen::Dynamic, kZ> PHt = CovarianceTimesHt<kZ>(obs);
  const MatrixZ S = InnovationCovarianceFromPHt<kZ>(obs, PHt);
  const Eigen::LLT<MatrixZ> llt(S);
  if (llt.info() != Eigen::Success) return false;  // never for R > 0; guard anyway
  const MatrixZ L_inv_t = llt.matrixL().solve(MatrixZ::Identity()).transpose();
  if (m_ + kZ > U_.cols()) U_.conservativeResize(Eigen::NoChange, 2 * U_.cols());
  auto V = U_.block(0, m_, n_, kZ);
  V.noalias() = PHt * L_inv_t;
  const Eigen::Matrix<double, kZ, 1> nu = obs.innovation;
  x_.head(n_) += V * (L_inv_t.transpose() * nu);
  WrapAngles();
  // Nearly every observation reads pose columns: keep them current in O(n) rather than
  // correcting them through all of U each time.
  for (const int p : pose_blocks_) {
    pose_cols_.block(0, 3 * pose_slot_[p], n_, 3).noalias() -=
        V * V.template middleRows<3>(BlockOffset(p)).transpose();
  }
  m_ += kZ;
  return true;
}

bool BlockEkf::Update(const Linearisation& obs) {
  return WithDim(static_cast<int>(obs.innovation.size()),
                 [&](auto Z) { return UpdateFixed<decltype(Z)::value>(obs); });
}

// S of an observation of two blocks a and b given P_aa: the one expression both the generic
// path and the association fast path evaluate, so that their distances agree bit for bit.
template <int kZ, int kD0, int kD1>
Eigen::Matrix<double, kZ, kZ> BlockEkf::TwoBlockS(const Eigen::Matrix<double, kD0, kD0>& P_00,
                                                  int a, int b,
                                                  const Eigen::Matrix<double, kZ, kD0>& J_0,
                                                  const Eigen::Matrix<double, kZ, kD1>& J_1,
                                                  const Eigen::Matrix<double, kZ, kZ>& R) const {
  const Eigen::Matrix<double, kD0, kD1> P_01 = CurrentBlockOf<kD0, kD1>(a, b);
  const Eigen::Matrix<double, kD1, kD1> P_11 = CurrentBlockOf<kD1, kD1>(b, b);
  const Eigen::Matrix<double, kZ, kZ> cross = J_0 * P_01 * J_1.transpose();
  return J_0 * P_00 * J_0.transpose() + cross + cross.transpose() +
         J_1 * P_11 * J_1.transpose() + R;
}

// S = H P Hᵀ + R from the few covariance blocks H touches, O(1) in n.
template <int kZ>
Eigen::Matrix<double, kZ, kZ> BlockEkf::InnovationCovarianceFixed(const Linearisation& obs) const {
  using MatrixZ = Eigen::Matrix<double, kZ, kZ>;
  const std::span<const BlockJacobian> H = obs.H.view();
  const MatrixZ R = obs.R;
  MatrixZ S = MatrixZ::Zero();
  if (H.size() == 2) {
    WithDims(BlockDim(H[0].block), BlockDim(H[1].block), [&](auto D0, auto D1) {
      constexpr int kD0 = decltype(D0)::value, kD1 = decltype(D1)::value;
      const Eigen::Matrix<double, kZ, kD0> J_0 = H[0].J;
      const Eigen::Matrix<double, kZ, kD1> J_1 = H[1].J;
      const Eigen::Matrix<double, kD0, kD0> P_00 = CurrentBlockOf<kD0, kD0>(H[0].block, H[0].block);
      S = TwoBlockS<kZ, kD0, kD1>(P_00, H[0].block, H[1].block, J_0, J_1, R);
    });
    return S;
  }
  for (const BlockJacobian& a : H) {
    for (const BlockJacobian& b : H) {
      S += a.J * CovarianceBlock(a.block, b.block) * b.J.transpose();
    }
  }
  return S + R;
}

BlockMatrix BlockEkf::InnovationCovariance(const Linearisation& obs) const {
  return WithDim(static_cast<int>(obs.innovation.size()), [&](auto Z) -> BlockMatrix {
    return InnovationCovarianceFixed<decltype(Z)::value>(obs);
  });
}

Eigen::Matrix3d BlockEkf::PoseCovarianceOf(int block) const {
  return CurrentBlockOf<3, 3>(block, block);
}

// Flattened: it runs for every landmark within reach of every observation, and out of line the
// small products and the 2×2 LLT cost as much in calls as in arithmetic.
__attribute__((flatten)) double BlockEkf::MahalanobisSquaredPosePoint(
    const PosePointObservation& obs) const {
  const Eigen::Matrix2d S =
      TwoBlockS<2, 3, 2>(*obs.P_pose, obs.pose, obs.point, obs.J_pose, obs.J_point, *obs.R);
  return obs.innovation.dot(S.llt().solve(obs.innovation));
}

double BlockEkf::MahalanobisSquared(const Linearisation& obs) const {
  return WithDim(static_cast<int>(obs.innovation.size()), [&](auto Z) {
    constexpr int kZ = decltype(Z)::value;
    const Eigen::Matrix<double, kZ, 1> nu = obs.innovation;
    const Eigen::Matrix<double, kZ, kZ> S = InnovationCovarianceFixed<kZ>(obs);
    return nu.dot(S.llt().solve(nu));
  });
}

Eigen::MatrixXd BlockEkf::JointInnovationCovariance(std::span<const Linearisation> obs) const {
  std::vector<int> start(obs.size() + 1, 0);
  for (std::size_t i = 0; i < obs.size(); ++i) {
    start[i + 1] = start[i] + static_cast<int>(obs[i].innovation.size());
  }
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(start.back(), start.back());
  for (std::size_t i = 0; i < obs.size(); ++i) {
    for (std::size_t j = 0; j < obs.size(); ++j) {
      auto S_ij = S.block(start[i], start[j], start[i + 1] - start[i], start[j + 1] - start[j]);
      for (const BlockJacobian& a : obs[i].H.view()) {
        for (const BlockJacobian& b : obs[j].H.view()) {
          S_ij += a.J * CovarianceBlock(a.block, b.block) * b.J.transpose();
        }
      }
      if (i == j) S_ij += obs[i].R;
    }
  }
  return S;
}

// The new block's cross-covariances with the poses, Σ_j J_j P_jp, as rows of the cached pose
// columns (the stored column is current too, but the cache is what later updates read).
template <int kD>
void BlockEkf::CachePoseRowsOfNewBlock(std::span<const BlockJacobian> J_new_blocks) {
  for (const int p : pose_blocks_) {
    auto rows = pose_cols_.block<kD, 3>(n_, 3 * pose_slot_[p]);
    for (std::size_t i = 0; i < J_new_blocks.size(); ++i) {
      const BlockJacobian& h = J_new_blocks[i];
      WithDim(BlockDim(h.block), [&](auto Dj) {
        constexpr int kDj = decltype(Dj)::value;
        const Eigen::Matrix<double, kD, kDj> J = h.J;
        const Eigen::Matrix<double, kDj, 3> P_jp =
            pose_cols_.block<kDj, 3>(BlockOffset(h.block), 3 * pose_slot_[p]);
        if (i == 0) {
          rows = J * P_jp;
        } else {
          rows += J * P_jp;
        }
      });
    }
  }
}

// SPEC S2, Eq. 8, with the covariance from the inverse model's Jacobians. The new rows of U are
// zero, so the stored cross-covariance column is already the current one.
template <int kD>
void BlockEkf::AugmentFixed(const BlockVector& mean, std::span<const BlockJacobian> J_new_blocks,
                            const BlockMatrix& J_new_z, const BlockMatrix& R) {
  const int n = n_;
  auto P_new = P_.block(0, n, n, kD);
  auto P_bb = P_.block<kD, kD>(n, n);
  WithDim(static_cast<int>(R.rows()), [&](auto Z) {
    constexpr int kZ = decltype(Z)::value;
    const Eigen::Matrix<double, kD, kZ> J_z = J_new_z;
    const Eigen::Matrix<double, kZ, kZ> R_z = R;
    if (J_new_blocks.size() == 1) {
      const int j = J_new_blocks[0].block;
      WithDim(BlockDim(j), [&](auto Dj) {
        constexpr int kDj = decltype(Dj)::value;
        const Eigen::Matrix<double, kD, kDj> J = J_new_blocks[0].J;
        Eigen::MatrixXd scratch;
        const Eigen::Ref<const Eigen::MatrixXd> P_j = BlockColumns(j, scratch);
        const Eigen::Matrix<double, kDj, kDj> P_jj = P_j.middleRows<kDj>(BlockOffset(j));
        P_new = P_j * J.transpose();
        P_bb = J * P_jj * J.transpose() + J_z * R_z * J_z.transpose();
      });
      return;
    }
    P_new.setZero();
    for (const BlockJacobian& h : J_new_blocks) {
      WithDim(BlockDim(h.block), [&](auto Dj) {
        const Eigen::Matrix<double, kD, decltype(Dj)::value> J = h.J;
        Eigen::MatrixXd scratch;
        P_new += BlockColumns(h.block, scratch) * J.transpose();
      });
    }
    Eigen::Matrix<double, kD, kD> P_sum = J_z * R_z * J_z.transpose();
    for (const BlockJacobian& h : J_new_blocks) {
      P_sum += h.J * P_new.middleRows(BlockOffset(h.block), BlockDim(h.block));
    }
    P_bb = P_sum;
  });
  U_.block(n, 0, kD, m_).setZero();
  if (m_ > 0) CachePoseRowsOfNewBlock<kD>(J_new_blocks);
  x_.segment<kD>(n) = mean;
}

int BlockEkf::Augment(int kind, const BlockVector& mean,
                      std::span<const BlockJacobian> J_new_blocks, const BlockMatrix& J_new_z,
                      const BlockMatrix& R) {
  const int dim = kinds_[kind].dim;
  Reserve(n_ + dim);
  WithDim(dim, [&](auto D) { AugmentFixed<decltype(D)::value>(mean, J_new_blocks, J_new_z, R); });
  return AppendBlock(kind);
}

}  // namespace slamkit
