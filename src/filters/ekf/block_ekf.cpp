#include "slamkit/filters/ekf/block_ekf.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "compressed_area.hpp"
#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

// A plain loop: the health checks run it at every step in Debug builds, where Eigen's expressions
// (allFinite()) are not inlined and cost several times more.
bool AllFinite(const double* v, int size) {
  for (int i = 0; i < size; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace

BlockEkf::BlockEkf(int initial_capacity) {
  RegisterKind({3, {2}, true});
  const int capacity = std::max(initial_capacity, 3);
  x_ = Eigen::VectorXd::Zero(capacity);
  P_ = Eigen::MatrixXd::Zero(capacity, capacity);
  U_ = Eigen::MatrixXd::Zero(capacity, 8);
}

int BlockEkf::RegisterKind(const BlockKind& kind) {
  if (kind.dim < 1 || kind.dim > kMaxBlockDim || (kind.is_pose && kind.dim != 3)) {
    throw std::invalid_argument("BlockEkf::RegisterKind: unsupported block dimension");
  }
  if (kind.is_pose && kind.normalise) {
    // Pose columns are cached during an update; a change of coordinates would have to follow them.
    throw std::invalid_argument("BlockEkf::RegisterKind: a pose kind cannot have a normalise step");
  }
  kinds_.push_back(kind);
  return static_cast<int>(kinds_.size()) - 1;
}

void BlockEkf::Clear() {
  area_.reset();
  spare_area_.reset();
  x_.setZero();
  P_.setZero();
  U_.setZero();
  pose_cols_.resize(0, 0);
  blocks_.clear();
  pose_blocks_.clear();
  pose_slot_.clear();
  angle_indices_.clear();
  normalised_blocks_.clear();
  n_ = 0;
  m_ = 0;
}

void BlockEkf::Reserve(int state_size) {
  const int capacity = static_cast<int>(x_.size());
  if (state_size <= capacity) return;
  ApplyPendingDowndate();  // growth is rare (doubling): simpler than carrying U over
  const int grown = std::max(state_size, 2 * capacity);
  U_ = Eigen::MatrixXd::Zero(grown, U_.cols());
  pose_cols_ = Eigen::MatrixXd::Zero(grown, pose_cols_.cols());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(grown);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(grown, grown);
  x.head(n_) = x_.head(n_);
  P.topLeftCorner(n_, n_).triangularView<Eigen::Upper>() = P_.topLeftCorner(n_, n_);
  x_.swap(x);
  P_.swap(P);
}

int BlockEkf::AddBlock(int kind, const BlockVector& mean, const BlockMatrix& cov) {
  if (area_) {
    const int local = area_->local.AddBlock(kind, mean, cov);
    area_->local_of.push_back(local);
    return RecordBlock(kind);
  }
  const int dim = kinds_[kind].dim;
  Reserve(n_ + dim);
  P_.block(0, n_, n_, dim).setZero();
  P_.block(n_, n_, dim, dim) = cov;
  U_.block(n_, 0, dim, m_).setZero();
  x_.segment(n_, dim) = mean;
  const int index = AppendBlock(kind);
  if (!kinds_[kind].is_pose && m_ > 0 && !pose_blocks_.empty()) {
    pose_cols_.middleRows(n_ - dim, dim).setZero();
  }
  return index;
}

BlockEkf BlockEkf::Marginal(std::span<const int> blocks) const {
  int dim = 0;
  for (const int b : blocks) dim += BlockDim(b);
  BlockEkf m(dim);
  for (std::size_t k = 1; k < kinds_.size(); ++k) m.RegisterKind(kinds_[k]);  // 0: the pose
  for (const int b : blocks) m.AddBlock(BlockKindOf(b), Mean(b), CovarianceBlock(b, b));
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i + 1; j < blocks.size(); ++j) {
      m.P_.block(m.BlockOffset(int(i)), m.BlockOffset(int(j)), m.BlockDim(int(i)),
                 m.BlockDim(int(j))) = CovarianceBlock(blocks[i], blocks[j]);
    }
  }
  return m;
}

int BlockEkf::RecordBlock(int kind) {
  const int dim = kinds_[kind].dim;
  const int index = NumBlocks();
  blocks_.push_back({kind, n_, dim});
  pose_slot_.push_back(-1);
  for (const int a : kinds_[kind].angle_components) angle_indices_.push_back(n_ + a);
  if (kinds_[kind].normalise) normalised_blocks_.push_back(index);
  n_ += dim;
  if (kinds_[kind].is_pose) {
    pose_slot_[index] = static_cast<int>(pose_blocks_.size());
    pose_blocks_.push_back(index);
  }
  return index;
}

// Records a block whose mean and covariance are already written at offset n_.
int BlockEkf::AppendBlock(int kind) {
  const int index = RecordBlock(kind);
  if (kinds_[kind].is_pose) {
    // A new pose slot: the cache is rebuilt from the current columns at the next update.
    ApplyPendingDowndate();
    pose_cols_ = Eigen::MatrixXd::Zero(x_.size(), 3 * static_cast<int>(pose_blocks_.size()));
  }
  return index;
}

Eigen::MatrixXd BlockEkf::CurrentColumns(int c, int k) const {
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

Eigen::Ref<const Eigen::MatrixXd> BlockEkf::BlockColumns(int block,
                                                         Eigen::MatrixXd& scratch) const {
  const Block& b = blocks_[block];
  const int slot = pose_slot_[block];
  if (m_ > 0 && slot >= 0) return pose_cols_.block(0, 3 * slot, n_, 3);
  scratch = CurrentColumns(b.offset, b.dim);
  return scratch;
}

void BlockEkf::StartPoseCache() {
  for (const int p : pose_blocks_) {
    pose_cols_.block(0, 3 * pose_slot_[p], n_, 3) = CurrentColumns(blocks_[p].offset, 3);
  }
}

// SPEC S2, Eq. 2 (Probabilistic Robotics Table 10.1): only the moving pose's rows change.
void BlockEkf::PredictPose(int block, const Pose2& moved, const Eigen::Matrix3d& J_x_x,
                           const ControlJacobian& J_x_u, const ControlCovariance& Q) {
  if (area_) {
    if (IsActive(block)) {
      area_->local.PredictPose(area_->local_of[block], moved, J_x_x, J_x_u, Q);
      return;
    }
    Synchronise();
  }
  ApplyPendingDowndate();
  const Eigen::Matrix3d& F = J_x_x;
  const ControlJacobian& G = J_x_u;
  const int o = blocks_[block].offset;
  const Eigen::Matrix3d P_vv = P_.block<3, 3>(o, o).selfadjointView<Eigen::Upper>();
  P_.block<3, 3>(o, o) = F * P_vv * F.transpose() + G * Q * G.transpose();
  if (o > 0) {
    // Column block: the cross-covariances with blocks before the pose.
    auto P_mv = P_.block(0, o, o, 3);
    P_mv = (P_mv * F.transpose()).eval();
  }
  if (n_ > o + 3) {
    // Row block: the cross-covariances with blocks after the pose.
    auto P_vm = P_.block(o, o + 3, 3, n_ - o - 3);
    P_vm = (F * P_vm).eval();
  }
  x_.segment<3>(o) = moved.vector();
}

void BlockEkf::WrapAngles() {
  for (const int i : angle_indices_) x_[i] = WrapAngle(x_[i]);
}

void BlockEkf::NormaliseBlocks() {
  for (const int b : normalised_blocks_) {
    const Block& block = blocks_[b];
    BlockVector mean = x_.segment(block.offset, block.dim);
    BlockMatrix J;
    if (!kinds_[block.kind].normalise(mean, &J)) continue;
    x_.segment(block.offset, block.dim) = mean;
    TransformBlockRows(b, J);
  }
}

// P ← T P Tᵀ with T the identity but for J on the block: its column above, its diagonal block
// and its row to the right, as PredictPose does for a pose.
void BlockEkf::TransformBlockRows(int block, const BlockMatrix& J) {
  const int o = blocks_[block].offset, d = blocks_[block].dim;
  const Eigen::MatrixXd P_bb = P_.block(o, o, d, d).selfadjointView<Eigen::Upper>();
  P_.block(o, o, d, d) = J * P_bb * J.transpose();
  if (o > 0) {
    auto P_ab = P_.block(0, o, o, d);
    P_ab = (P_ab * J.transpose()).eval();
  }
  if (n_ > o + d) {
    auto P_bc = P_.block(o, o + d, d, n_ - o - d);
    P_bc = (J * P_bc).eval();
  }
}

Eigen::MatrixXd BlockEkf::Covariance() const {
  if (area_) return CompressedCovariance();
  Eigen::MatrixXd P = P_.topLeftCorner(n_, n_).selfadjointView<Eigen::Upper>();
  if (m_ > 0) P.noalias() -= U_.topLeftCorner(n_, m_) * U_.topLeftCorner(n_, m_).transpose();
  return P;
}

// The stored triangle is symmetric by construction once the downdate is applied, so the symmetry
// test bites on the product U Uᵀ of a pending one; finiteness and PSD bite either way.
std::optional<std::string> BlockEkf::HealthProblem(const StateHealthParams& params,
                                                   bool check_psd) const {
  if (area_) return AreaHealthProblem(params, check_psd);
  if (m_ > 0 || check_psd) return GaussianHealthProblem(State(), Covariance(), params, check_psd);
  // Nothing pending and no PSD test: the stored triangle is the covariance, so checking its
  // entries is all that is left, without the O(n²) copy (the every-update check in Debug).
  if (!AllFinite(x_.data(), n_)) return NonFiniteProblem(State(), "mean");
  for (int j = 0; j < n_; ++j) {
    if (!AllFinite(&P_(0, j), j + 1)) return NonFiniteProblem(Covariance(), "covariance");
  }
  return std::nullopt;
}

bool BlockEkf::BlockFinite(int block) const {
  if (area_) return Mean(block).allFinite() && CovarianceBlock(block, block).allFinite();
  const int o = blocks_[block].offset, d = blocks_[block].dim;
  if (!x_.segment(o, d).allFinite()) return false;
  if (m_ > 0) {
    Eigen::MatrixXd scratch;
    return BlockColumns(block, scratch).allFinite();
  }
  // In place, on the stored triangle: the column above the block and the block's upper triangle,
  // then the row to its right, d entries of each later column.
  for (int j = o; j < o + d; ++j) {
    if (!AllFinite(&P_(0, j), j + 1)) return false;
  }
  for (int j = o + d; j < n_; ++j) {
    if (!AllFinite(&P_(o, j), d)) return false;
  }
  return true;
}

void BlockEkf::CheckHealth(const StateHealthParams& params, bool check_psd,
                           std::string_view where) const {
  if (auto problem = HealthProblem(params, check_psd)) ThrowNumericalError(where, *problem);
}

}  // namespace slamkit
