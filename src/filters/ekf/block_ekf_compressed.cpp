// BlockEkf's compressed updates (Guivant & Nebot, "Optimization of the Simultaneous Localization
// and Map-Building Algorithm for Real-Time Implementation", IEEE T-RA 17(3), 2001, Sec. III):
// opening an area and the global update (reads through an open area: block_ekf_area_reads.cpp).

#include <algorithm>
#include <stdexcept>

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
