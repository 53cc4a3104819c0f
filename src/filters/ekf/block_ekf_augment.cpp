// BlockEkf's augmentation with a new block, dispatched on the dimensions involved.

#include <algorithm>

#include "block_dispatch.hpp"
#include "compressed_area.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

using internal::WithDim;
using internal::WithMeasurementDim;

// The new block's cross-covariances with the poses, Σ_j J_j P_jp, as rows of the cached pose
// columns (the stored column is current too, but the cache is what later updates read).
template <int kD>
void BlockEkf::CachePoseRowsOfNewBlock(int dim, std::span<const BlockJacobian> J_new_blocks) {
  for (const int p : pose_blocks_) {
    auto rows = pose_cols_.block<kD, 3>(n_, 3 * pose_slot_[p], dim, 3);
    for (std::size_t i = 0; i < J_new_blocks.size(); ++i) {
      const BlockJacobian& h = J_new_blocks[i];
      WithDim<kD != Eigen::Dynamic>(BlockDim(h.block), [&](auto Dj) {
        constexpr int kDj = decltype(Dj)::value;
        const SmallMatrix<kD, kDj> J = h.J;
        const SmallMatrix<kDj, 3> P_jp = pose_cols_.block<kDj, 3>(
            BlockOffset(h.block), 3 * pose_slot_[p], BlockDim(h.block), 3);
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
  const int n = n_, d = static_cast<int>(mean.size());
  auto P_new = P_.block(0, n, n, d);
  auto P_bb = P_.block<kD, kD>(n, n, d, d);
  const auto with_z = [&](auto&& f) {
    if constexpr (kD == Eigen::Dynamic) {
      return f(std::integral_constant<int, Eigen::Dynamic>{});
    } else {
      return WithMeasurementDim(static_cast<int>(R.rows()), f);
    }
  };
  with_z([&](auto Z) {
    constexpr int kZ = decltype(Z)::value;
    const SmallMatrix<kD, kZ> J_z = J_new_z;
    const SmallMatrix<kZ, kZ> R_z = R;
    if (J_new_blocks.size() == 1) {
      const int j = J_new_blocks[0].block;
      WithDim<kZ != Eigen::Dynamic>(BlockDim(j), [&](auto Dj) {
        constexpr int kDj = decltype(Dj)::value;
        const SmallMatrix<kD, kDj> J = J_new_blocks[0].J;
        Eigen::MatrixXd scratch;
        const Eigen::Ref<const Eigen::MatrixXd> P_j = BlockColumns(j, scratch);
        const SmallMatrix<kDj, kDj> P_jj =
            P_j.middleRows<kDj>(BlockOffset(j), BlockDim(j));
        P_new = P_j * J.transpose();
        P_bb = J * P_jj * J.transpose() + J_z * R_z * J_z.transpose();
      });
      return;
    }
    P_new.setZero();
    for (const BlockJacobian& h : J_new_blocks) {
      WithDim<kZ != Eigen::Dynamic>(BlockDim(h.block), [&](auto Dj) {
        const SmallMatrix<kD, decltype(Dj)::value> J = h.J;
        Eigen::MatrixXd scratch;
        P_new += BlockColumns(h.block, scratch) * J.transpose();
      });
    }
    SmallMatrix<kD, kD> P_sum = J_z * R_z * J_z.transpose();
    for (const BlockJacobian& h : J_new_blocks) {
      P_sum += h.J * P_new.middleRows(BlockOffset(h.block), BlockDim(h.block));
    }
    P_bb = P_sum;
  });
  U_.block(n, 0, d, m_).setZero();
  if (m_ > 0) CachePoseRowsOfNewBlock<kD>(d, J_new_blocks);
  x_.segment<kD>(n, d) = mean;
}

int BlockEkf::Augment(int kind, const BlockVector& mean,
                      std::span<const BlockJacobian> J_new_blocks, const BlockMatrix& J_new_z,
                      const BlockMatrix& R) {
  if (area_) {
    BlockJacobians local;
    for (const BlockJacobian& h : J_new_blocks) local.Add(area_->local_of[h.block], h.J);
    const auto view = local.view();
    if (std::all_of(view.begin(), view.end(), [](const BlockJacobian& h) { return h.block >= 0; })) {
      area_->local_of.push_back(area_->local.Augment(kind, mean, view, J_new_z, R));
      return RecordBlock(kind);
    }
    Synchronise();
  }
  const int dim = kinds_[kind].dim;
  Reserve(n_ + dim);
  WithDim(dim, [&](auto D) { AugmentFixed<decltype(D)::value>(mean, J_new_blocks, J_new_z, R); });
  return AppendBlock(kind);
}

}  // namespace slamkit
