// BlockEkf's compressed updates (Guivant & Nebot, "Optimization of the Simultaneous Localization
// and Map-Building Algorithm for Real-Time Implementation", IEEE T-RA 17(3), 2001, Sec. III):
// opening an area, the global update, and reads of the whole state while an area is open.


#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>

#include "slamkit/core/angle.hpp"
#include "compressed_area.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {


BlockEkf::BlockEkf(const BlockEkf& other)
    : kinds_(other.kinds_),
      blocks_(other.blocks_),
      pose_blocks_(other.pose_blocks_),
      pose_slot_(other.pose_slot_),
      angle_indices_(other.angle_indices_),
      normalised_blocks_(other.normalised_blocks_),
      n_(other.n_),
      x_(other.x_),
      P_(other.P_),
      U_(other.U_),
      pose_cols_(other.pose_cols_),
      m_(other.m_),
      area_(other.area_ ? std::make_unique<CompressedArea>(*other.area_) : nullptr) {}  // no spare

BlockEkf& BlockEkf::operator=(const BlockEkf& other) {
  if (this != &other) *this = BlockEkf(other);
  return *this;
}

BlockEkf::BlockEkf(BlockEkf&& other) noexcept = default;
BlockEkf& BlockEkf::operator=(BlockEkf&& other) noexcept = default;
BlockEkf::~BlockEkf() = default;

bool BlockEkf::HasPendingDowndate() const {
  return area_ ? area_->local.HasPendingDowndate() : m_ > 0;
}

bool BlockEkf::InArea(int block) const { return area_->local_of[block] >= 0; }

int BlockEkf::ActiveSize() const {
  return area_ ? area_->local.StateSize() - area_->a0 : 0;
}

// Guivant & Nebot 2001, Sec. III-A: the area's filter starts as the marginal of A₀, with Z beside
// it (Cov(A₀, Z) = I: φ = I, ψ = 0, θ = 0).
void BlockEkf::Compress(std::span<const int> active) {
  Synchronise();
  ApplyPendingDowndate();
  std::unique_ptr<CompressedArea> area =
      spare_area_ ? std::move(spare_area_) : std::make_unique<CompressedArea>();
  area->local_of.assign(blocks_.size(), -1);
  area->a0_index.clear();
  for (std::size_t i = 0; i < active.size(); ++i) {
    const int b = active[i];
    if (area->local_of[b] >= 0) throw std::invalid_argument("BlockEkf::Compress: a repeated block");
    area->local_of[b] = static_cast<int>(i);
    for (int r = 0; r < BlockDim(b); ++r) area->a0_index.push_back(BlockOffset(b) + r);
  }
  const int a0 = static_cast<int>(area->a0_index.size());
  area->a0 = a0;
  area->k0 = static_cast<int>(active.size());
  area->n0 = n_;
  area->StartLocal(*this, active);
  area_ = std::move(area);
}

// The area's filter: A₀'s marginal, then Z. Its storage is the last area's when that fits (the
// area's size changes little from one to the next), with room for the blocks an area adds.
void BlockEkf::CompressedArea::StartLocal(const BlockEkf& whole, std::span<const int> active) {
  const int capacity = 2 * a0 + std::max(64, a0 / 2);
  const int kinds = static_cast<int>(whole.kinds_.size());
  if (local.Capacity() >= capacity && local.Capacity() <= 2 * capacity &&
      static_cast<int>(local.kinds_.size()) == kinds + kMaxBlockDim) {
    local.Clear();
  } else {
    local = BlockEkf(capacity);
    for (int k = 1; k < kinds; ++k) local.RegisterKind(whole.kinds_[k]);  // 0: the pose
    for (int d = 1; d <= kMaxBlockDim; ++d) local.RegisterKind({d, {}, false});
  }
  for (const int b : active) {
    const Block& block = whole.blocks_[b];
    local.AddBlock(block.kind, whole.x_.segment(block.offset, block.dim),
                   BlockMatrix::Zero(block.dim, block.dim));
  }
  // A₀'s joint covariance, entry by entry from the whole state's triangle.
  for (int j = 0; j < a0; ++j) {
    for (int i = 0; i <= j; ++i) {
      const int p = a0_index[i], q = a0_index[j];
      local.P_(i, j) = p <= q ? whole.P_(p, q) : whole.P_(q, p);
    }
  }
  for (std::size_t i = 0; i < active.size(); ++i) {
    const int d = whole.blocks_[active[i]].dim;
    const int z = local.AddBlock(kinds + d - 1, BlockVector::Zero(d), BlockMatrix::Zero(d, d));
    for (int r = 0; r < d; ++r) {
      local.P_(local.BlockOffset(static_cast<int>(i)) + r, local.BlockOffset(z) + r) = 1.0;
    }
  }
}

// Guivant & Nebot 2001, Sec. III-B (the global update): x_B += C θ, P_BB −= C ψ Cᵀ and
// P_{A,B} = φ Cᵀ, then A's own mean and covariance from the area's filter.
void BlockEkf::Synchronise() {
  if (!area_) return;
  std::unique_ptr<CompressedArea> area = std::move(area_);
  spare_area_ = nullptr;
  area->local.ApplyPendingDowndate();
  const int n = n_;
  const Eigen::MatrixXd C = area->CrossRowsOfAll(*this);
  x_.head(area->n0) += C * area->Theta();
  n_ = area->n0;  // the triangle update and the growth see the old state
  SubtractFromTriangle(C * area->Psi(), C);
  if (n > x_.size()) Reserve(n);
  n_ = n;
  WriteAreaBack(*area, C);
  pose_cols_ = Eigen::MatrixXd::Zero(x_.size(), 3 * static_cast<int>(pose_blocks_.size()));
  WrapAngles();
  NormaliseBlocks();
  spare_area_ = std::move(area);
}

// The area's blocks (A₀ and those added since) from its filter: their means, their covariance
// and their cross-covariance φ Cᵀ with the rest.
void BlockEkf::WriteAreaBack(const CompressedArea& area, const Eigen::MatrixXd& C) {
  const BlockEkf& local = area.local;
  std::vector<int> local_index, whole_index;
  for (int b = 0; b < NumBlocks(); ++b) {
    const int lb = area.local_of[b];
    if (lb < 0) continue;
    for (int r = 0; r < blocks_[b].dim; ++r) {
      local_index.push_back(local.BlockOffset(lb) + r);
      whole_index.push_back(blocks_[b].offset + r);
    }
  }
  const int a = static_cast<int>(local_index.size()), a0 = area.a0, n0 = area.n0;
  // The area's filter has nothing pending: its triangle is its covariance.
  const auto local_cov = [&local](int p, int q) { return p <= q ? local.P_(p, q) : local.P_(q, p); };
  Eigen::MatrixXd phi(a, a0);
  for (int j = 0; j < a0; ++j) {
    for (int i = 0; i < a; ++i) phi(i, j) = local_cov(local_index[i], a0 + j);
  }
  const Eigen::MatrixXd cross = phi * C.transpose();  // a × n0; zero against A₀
  std::vector<char> in_area(n_, 0);
  for (const int w : whole_index) in_area[w] = 1;
  for (int i = 0; i < a; ++i) {
    const int w = whole_index[i];
    x_[w] = local.x_[local_index[i]];
    for (int j = 0; j < n0; ++j) {
      if (!in_area[j]) (w <= j ? P_(w, j) : P_(j, w)) = cross(i, j);
    }
    for (int k = 0; k < a; ++k) {
      const int v = whole_index[k];
      if (w <= v) P_(w, v) = local_cov(local_index[i], local_index[k]);
    }
  }
}

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

// The area's filter without Z (whose covariance −ψ is not one): the blocks an update changes.
// The rest changes by C θ and C ψ Cᵀ, checked when Synchronise() applies them.
std::optional<std::string> BlockEkf::AreaHealthProblem(const StateHealthParams& params,
                                                       bool check_psd) const {
  const BlockEkf& local = area_->local;
  std::vector<int> blocks;
  for (int b = 0; b < local.NumBlocks(); ++b) {
    if (b < area_->k0 || b >= 2 * area_->k0) blocks.push_back(b);
  }
  return local.Marginal(blocks).HealthProblem(params, check_psd);
}

Eigen::MatrixXd BlockEkf::CurrentRange(int r, int rn, int c, int cn) const {
  Eigen::MatrixXd block(rn, cn);
  for (int j = 0; j < cn; ++j) {
    for (int i = 0; i < rn; ++i) {
      const int p = r + i, q = c + j;
      block(i, j) = p <= q ? P_(p, q) : P_(q, p);
    }
  }
  if (m_ > 0) block.noalias() -= U_.block(r, 0, rn, m_) * U_.block(c, 0, cn, m_).transpose();
  return block;
}

}  // namespace slamkit
