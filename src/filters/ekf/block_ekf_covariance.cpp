// The parts of BlockEkf that read the current covariance (the stored triangle less the
// deferred factor U Uᵀ) in fixed-size blocks: blocks, the innovation covariance and Mahalanobis
// distances, and the deferred downdate itself.

#include <tbb/parallel_for.h>

#include <Eigen/Cholesky>

#include "block_dispatch.hpp"
#include "compressed_area.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

using internal::WithDim;
using internal::WithDims;
using internal::WithMeasurementDim;

// Rows [r, r + rows) × columns [c, c + cols); R and C are rows and cols, or Eigen::Dynamic.
template <int R, int C>
SmallMatrix<R, C> BlockEkf::CurrentBlock(int r, int c, int rows, int cols) const {
  SmallMatrix<R, C> block = P_.block<R, C>(r, c, rows, cols);
  if constexpr (R == C) {
    if (r == c) block = P_.block<R, C>(r, c, rows, cols).template selfadjointView<Eigen::Upper>();
  }
  if (m_ > 0) {
    block.noalias() -= U_.block(r, 0, rows, m_) * U_.block(c, 0, cols, m_).transpose();
  }
  return block;
}

// Block (a, b) of the current covariance; the stored triangle holds whichever lies above.
template <int R, int C>
SmallMatrix<R, C> BlockEkf::CurrentBlockOf(int a, int b) const {
  const Block &ba = blocks_[a], &bb = blocks_[b];
  if (ba.offset <= bb.offset) return CurrentBlock<R, C>(ba.offset, bb.offset, ba.dim, bb.dim);
  return CurrentBlock<C, R>(bb.offset, ba.offset, bb.dim, ba.dim).transpose();
}

Eigen::MatrixXd BlockEkf::CovarianceBlock(int a, int b) const {
  if (area_) return CompressedCovarianceBlock(a, b);
  return WithDims(BlockDim(a), BlockDim(b), [&](auto R, auto C) -> Eigen::MatrixXd {
    return CurrentBlockOf<decltype(R)::value, decltype(C)::value>(a, b);
  });
}

void BlockEkf::ApplyPendingDowndate() {
  if (area_) {
    area_->local.ApplyPendingDowndate();
    return;
  }
  if (m_ == 0) return;
  SubtractFromTriangle(U_.topLeftCorner(n_, m_), U_.topLeftCorner(n_, m_));
  m_ = 0;
  NormaliseBlocks();
}

void BlockEkf::SubtractFromTriangle(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                    const Eigen::Ref<const Eigen::MatrixXd>& B) {
  // Fixed blocks, whatever the thread count, so the sums and hence the bits never change.
  constexpr int kBlock = 128;
  const int blocks = (n_ + kBlock - 1) / kBlock;
  tbb::parallel_for(0, blocks, [&](int b) {
    const int j0 = b * kBlock, w = std::min(kBlock, n_ - j0);
    const auto B_j = B.middleRows(j0, w);
    P_.block(0, j0, j0, w).noalias() -= A.topRows(j0) * B_j.transpose();
    P_.block(j0, j0, w, w).triangularView<Eigen::Upper>() -= A.middleRows(j0, w) * B_j.transpose();
  });
}

// S of an observation of two blocks a and b given P_aa: the one expression both the generic
// path and the association fast path evaluate, so that their distances agree bit for bit.
template <int kZ, int kD0, int kD1>
SmallMatrix<kZ, kZ> BlockEkf::TwoBlockS(const SmallMatrix<kD0, kD0>& P_00,
                                                  int a, int b,
                                                  const SmallMatrix<kZ, kD0>& J_0,
                                                  const SmallMatrix<kZ, kD1>& J_1,
                                                  const SmallMatrix<kZ, kZ>& R) const {
  const SmallMatrix<kD0, kD1> P_01 = CurrentBlockOf<kD0, kD1>(a, b);
  const SmallMatrix<kD1, kD1> P_11 = CurrentBlockOf<kD1, kD1>(b, b);
  const SmallMatrix<kZ, kZ> cross = J_0 * P_01 * J_1.transpose();
  return J_0 * P_00 * J_0.transpose() + cross + cross.transpose() +
         J_1 * P_11 * J_1.transpose() + R;
}

// S = H P Hᵀ + R from the few covariance blocks H touches, O(1) in n.
template <int kZ>
SmallMatrix<kZ, kZ> BlockEkf::InnovationCovarianceFixed(const Linearisation& obs) const {
  using MatrixZ = SmallMatrix<kZ, kZ>;
  const std::span<const BlockJacobian> H = obs.H.view();
  const MatrixZ R = obs.R;
  const int z = static_cast<int>(obs.innovation.size());
  MatrixZ S = MatrixZ::Zero(z, z);
  if (H.size() == 2) {
    WithDims<kZ != Eigen::Dynamic>(BlockDim(H[0].block), BlockDim(H[1].block), [&](auto D0, auto D1) {
      constexpr int kD0 = decltype(D0)::value, kD1 = decltype(D1)::value;
      const SmallMatrix<kZ, kD0> J_0 = H[0].J;
      const SmallMatrix<kZ, kD1> J_1 = H[1].J;
      const SmallMatrix<kD0, kD0> P_00 = CurrentBlockOf<kD0, kD0>(H[0].block, H[0].block);
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
  if (area_) {
    if (const std::optional<Linearisation> local = ToArea(obs)) {
      return area_->local.InnovationCovariance(*local);
    }
    return GenericInnovationCovariance(obs);
  }
  return WithMeasurementDim(static_cast<int>(obs.innovation.size()), [&](auto Z) -> BlockMatrix {
    return InnovationCovarianceFixed<decltype(Z)::value>(obs);
  });
}

Eigen::Matrix3d BlockEkf::PoseCovarianceOf(int block) const {
  if (area_) return CovarianceBlock(block, block);
  return CurrentBlockOf<3, 3>(block, block);
}

// Flattened: it runs for every landmark within reach of every observation, and out of line the
// small products and the 2×2 LLT cost as much in calls as in arithmetic.
__attribute__((flatten)) double BlockEkf::MahalanobisSquaredPosePoint(
    const PosePointObservation& obs) const {
  if (area_) [[unlikely]] {
    return CompressedMahalanobisSquaredPosePoint(obs);
  }
  const Eigen::Matrix2d S =
      TwoBlockS<2, 3, 2>(*obs.P_pose, obs.pose, obs.point, obs.J_pose, obs.J_point, *obs.R);
  return obs.innovation.dot(S.llt().solve(obs.innovation));
}

double BlockEkf::MahalanobisSquared(const Linearisation& obs) const {
  if (area_) {
    if (const std::optional<Linearisation> local = ToArea(obs)) {
      return area_->local.MahalanobisSquared(*local);
    }
    const BlockMatrix S = GenericInnovationCovariance(obs);
    return obs.innovation.dot(S.llt().solve(obs.innovation));
  }
  return WithMeasurementDim(static_cast<int>(obs.innovation.size()), [&](auto Z) {
    constexpr int kZ = decltype(Z)::value;
    const SmallMatrix<kZ, 1> nu = obs.innovation;
    const SmallMatrix<kZ, kZ> S = InnovationCovarianceFixed<kZ>(obs);
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


}  // namespace slamkit
