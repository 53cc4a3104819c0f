// BlockEkf's reads of the whole state while a compressed area is open (Guivant & Nebot, IEEE
// T-RA 17(3), 2001, Eqs. 22-24): a block outside the area is x⁰ + C θ, its covariance
// P⁰ − C ψ Cᵀ, and its cross-covariance with the area φ Cᵀ.

#include <Eigen/Cholesky>
#include <optional>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "compressed_area.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

std::optional<Linearisation> BlockEkf::ToArea(const Linearisation& obs) const {
  Linearisation renamed = obs;
  for (int i = 0; i < renamed.H.size; ++i) {
    int& block = renamed.H.items[i].block;
    block = area_->local_of[block];
    if (block < 0) return std::nullopt;
  }
  return renamed;
}

BlockMatrix BlockEkf::GenericInnovationCovariance(const Linearisation& obs) const {
  BlockMatrix S = obs.R;
  for (const BlockJacobian& a : obs.H.view()) {
    for (const BlockJacobian& b : obs.H.view()) {
      S += a.J * CovarianceBlock(a.block, b.block) * b.J.transpose();
    }
  }
  return S;
}

__attribute__((noinline)) double BlockEkf::CompressedMahalanobisSquaredPosePoint(const PosePointObservation& obs) const {
  PosePointObservation local = obs;
  local.pose = area_->local_of[obs.pose];
  local.point = area_->local_of[obs.point];
  if (local.pose >= 0 && local.point >= 0) {
    return area_->local.MahalanobisSquaredPosePoint(local);
  }
  const Eigen::Matrix<double, 2, 3> cross = obs.J_point * CovarianceBlock(obs.point, obs.pose);
  const Eigen::Matrix2d S_cross = cross * obs.J_pose.transpose();
  const Eigen::Matrix2d S = obs.J_pose * *obs.P_pose * obs.J_pose.transpose() + S_cross +
                            S_cross.transpose() +
                            obs.J_point * CovarianceBlock(obs.point, obs.point) *
                                obs.J_point.transpose() +
                            *obs.R;
  return obs.innovation.dot(S.llt().solve(obs.innovation));
}

BlockVector BlockEkf::CompressedMean(int block) const {
  const CompressedArea& area = *area_;
  const int lb = area.local_of[block];
  if (lb >= 0) return area.local.Mean(lb);
  BlockVector mean;
  OutsideMean(block, &mean);
  return mean;
}

// A block outside the area as the dense filter holds it: x⁰ + C θ, its angles wrapped and its
// kind's normalise step applied (Synchronise() applies it to the stored state; the dense filter
// after every downdate). Returns that step's Jacobian (the identity when it changes nothing),
// which a covariance read applies too.
BlockMatrix BlockEkf::OutsideMean(int block, BlockVector* mean) const {
  const Block& b = blocks_[block];
  *mean = x_.segment(b.offset, b.dim) + area_->CrossRows(*this, block) * area_->Theta();
  for (const int c : kinds_[b.kind].angle_components) (*mean)[c] = WrapAngle((*mean)[c]);
  BlockMatrix J = BlockMatrix::Identity(b.dim, b.dim);
  if (const BlockNormaliser normalise = kinds_[b.kind].normalise) {
    if (!normalise(*mean, &J)) J = BlockMatrix::Identity(b.dim, b.dim);
  }
  return J;
}

// The normalise step's Jacobian of a block outside the area (see OutsideMean).
BlockMatrix BlockEkf::OutsideNormaliser(int block) const {
  BlockVector mean;
  return OutsideMean(block, &mean);
}

Eigen::MatrixXd BlockEkf::CompressedCovarianceBlock(int a, int b) const {
  const CompressedArea& area = *area_;
  const int la = area.local_of[a], lb = area.local_of[b];
  if (la >= 0 && lb >= 0) return area.local.CovarianceBlock(la, lb);
  Eigen::MatrixXd P;
  if (la >= 0) {
    P = area.Phi(la) * area.CrossRows(*this, b).transpose();
  } else if (lb >= 0) {
    P = area.CrossRows(*this, a) * area.Phi(lb).transpose();
  } else {
    P = OutsideCovarianceBlock(a, b);
  }
  // An outside block's normalise step, as its mean's read applies it (OutsideMean).
  if (la < 0 && kinds_[blocks_[a].kind].normalise) P = OutsideNormaliser(a) * P;
  if (lb < 0 && kinds_[blocks_[b].kind].normalise) P = P * OutsideNormaliser(b).transpose();
  return P;
}

std::vector<Eigen::MatrixXd> BlockEkf::DiagonalBlocks(std::span<const int> blocks) const {
  std::vector<Eigen::MatrixXd> out(blocks.size());
  if (!area_) {
    for (std::size_t i = 0; i < blocks.size(); ++i) out[i] = CovarianceBlock(blocks[i], blocks[i]);
    return out;
  }
  // The outside blocks' rows of C stacked, times ψ once: P_bb = P⁰_bb − C_b ψ C_bᵀ.
  const CompressedArea& area = *area_;
  std::vector<int> outside_rows(blocks.size(), -1);
  int rows = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (area.local_of[blocks[i]] >= 0) {
      out[i] = area.local.CovarianceBlock(area.local_of[blocks[i]], area.local_of[blocks[i]]);
    } else {
      outside_rows[i] = rows;
      rows += BlockDim(blocks[i]);
    }
  }
  Eigen::MatrixXd C(rows, area.a0);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (outside_rows[i] >= 0) {
      C.middleRows(outside_rows[i], BlockDim(blocks[i])) = area.CrossRows(*this, blocks[i]);
    }
  }
  const Eigen::MatrixXd C_psi = C * area.Psi();
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (outside_rows[i] < 0) continue;
    const Block& b = blocks_[blocks[i]];
    Eigen::MatrixXd P(b.dim, b.dim);
    for (int r = 0; r < b.dim; ++r) {
      for (int c = 0; c < b.dim; ++c) {
        const int p = b.offset + r, q = b.offset + c;
        P(r, c) = (p <= q ? P_(p, q) : P_(q, p)) -
                  C_psi.row(outside_rows[i] + r).dot(C.row(outside_rows[i] + c));
      }
    }
    if (kinds_[b.kind].normalise) {
      const BlockMatrix J = OutsideNormaliser(blocks[i]);
      P = J * P * J.transpose();
    }
    out[i] = P;
  }
  return out;
}

// Covariance block (a, b) of two blocks outside the area, before their normalise steps.
Eigen::MatrixXd BlockEkf::OutsideCovarianceBlock(int a, int b) const {
  const CompressedArea& area = *area_;
  const Eigen::MatrixXd C_a = area.CrossRows(*this, a), C_b = area.CrossRows(*this, b);
  const Block &ba = blocks_[a], &bb = blocks_[b];
  Eigen::MatrixXd P0(ba.dim, bb.dim);
  for (int r = 0; r < ba.dim; ++r) {
    for (int c = 0; c < bb.dim; ++c) {
      const int i = ba.offset + r, k = bb.offset + c;
      P0(r, c) = i <= k ? P_(i, k) : P_(k, i);
    }
  }
  return P0 - C_a * area.Psi() * C_b.transpose();
}

// The whole covariance as Synchronise() would leave it, without closing the area: O(n²·a₀).
Eigen::MatrixXd BlockEkf::CompressedCovariance() const {
  BlockEkf whole(*this);
  whole.Synchronise();
  return whole.Covariance();
}

Eigen::VectorXd BlockEkf::State() const {
  if (!area_) return x_.head(n_);
  Eigen::VectorXd x(n_);
  for (int b = 0; b < NumBlocks(); ++b) x.segment(BlockOffset(b), BlockDim(b)) = Mean(b);
  return x;
}

}  // namespace slamkit
