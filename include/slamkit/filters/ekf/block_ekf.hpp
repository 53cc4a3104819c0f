#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/state_health.hpp"
#include "slamkit/models/motion_model.hpp"

namespace slamkit {

// Largest dimension of one state block or one observation (an SE(2) pose, a relative-pose
// measurement). Small matrices are bounded by it so that they live on the stack.
inline constexpr int kMaxBlockDim = 3;
// Largest number of state blocks one observation or one new block depends on.
inline constexpr int kMaxObservedBlocks = 4;

using BlockVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBlockDim, 1>;
// R × C with R and C fixed, or Eigen::Dynamic bounded by kMaxBlockDim: the typed update's small
// matrices (see block_dispatch.hpp), whose products stay coefficient-based either way.
template <int R, int C>
using SmallMatrix =
    Eigen::Matrix<double, R, C, 0, (R == Eigen::Dynamic ? kMaxBlockDim : R),
                  (C == Eigen::Dynamic ? kMaxBlockDim : C)>;
// n × C, C as in SmallMatrix: P Hᵀ and the like.
template <int C>
using TallMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, C, 0, Eigen::Dynamic, (C == Eigen::Dynamic ? kMaxBlockDim : C)>;
using BlockMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockDim, kMaxBlockDim>;

// Brings a block's mean back to its canonical form (a world line's ρ ≥ 0, SPEC S1) by an affine
// change of coordinates b' = J b + c. Returns false when `mean` is canonical already; otherwise
// rewrites it and sets *J (dim × dim, invertible) so that the covariance follows the change.
using BlockNormaliser = bool (*)(BlockVector& mean, BlockMatrix* J);

// What one kind of block in the state is: its dimension and which of its components are angles
// (kept wrapped to [-π, π) after every update). Pose blocks get their covariance columns cached
// during a deferred update, since nearly every observation touches a pose. A non-pose kind may
// have a `normalise` step, run on each of its blocks when a deferred downdate is applied.
struct BlockKind {
  int dim = 2;
  std::vector<int> angle_components;
  bool is_pose = false;
  BlockNormaliser normalise = nullptr;
};

// The SE(2) vehicle pose (x, y, θ): the kind every BlockEkf registers first, as kind 0.
inline constexpr int kPoseKind = 0;

// The derivative of a function (a prediction, a new block) with respect to one state block.
struct BlockJacobian {
  int block = -1;
  BlockMatrix J;  // output dim × the block's dim
};

// A short list of block Jacobians (an observation touches a few blocks), kept on the stack.
struct BlockJacobians {
  std::array<BlockJacobian, kMaxObservedBlocks> items;
  int size = 0;

  void Add(int block, const BlockMatrix& J) { items[size++] = {block, J}; }
  std::span<const BlockJacobian> view() const { return {items.data(), std::size_t(size)}; }
};

// An observation linearised at the current mean: ν = z − h(x̂) (angles wrapped), the Jacobian
// of h with respect to each block it touches (zero elsewhere) and the measurement noise R.
struct Linearisation {
  BlockVector innovation;
  BlockJacobians H;
  BlockMatrix R;
};

// A 2-D observation of one point block from one pose block at fixed sizes: what association
// scores against every landmark. The pose's current covariance is computed once by the caller
// (PoseCovarianceOf) and shared by all candidates, rather than once per candidate.
struct PosePointObservation {
  int pose = -1;
  int point = -1;
  Eigen::Vector2d innovation;
  Eigen::Matrix<double, 2, 3> J_pose;
  Eigen::Matrix2d J_point;
  const Eigen::Matrix2d* R = nullptr;
  const Eigen::Matrix3d* P_pose = nullptr;
};

// EKF on a state made of blocks: vehicle poses and landmarks of several kinds (SPEC S1 item 1,
// S2, S3), x = [b_0, b_1, …], each block a contiguous segment.
//
// Only the upper triangle of the covariance is stored and updated: prediction touches one pose's
// rows (O(n)), each observation's sequential update is a symmetric rank-m downdate of that
// triangle (O(n²)), and augmentation appends a block's columns (O(n)).
//
// Updates are deferred: the covariance is kept as P₀ − U Uᵀ, each observation reads the few
// columns it needs through that correction (O(n·m)) and appends its columns to U, and the
// downdate P₀ − U Uᵀ is applied in one pass over the triangle by ApplyPendingDowndate() (called
// by whatever needs the stored triangle: prediction, growth, the filter at the end of a scan).
// The result is the sequential EKF's: each observation is linearised at the mean its
// predecessors left.
//
// Compressed updates (Guivant & Nebot, IEEE T-RA 2001): after Compress(active), predictions,
// updates and augmentations that touch only the active blocks (and blocks added since) cost
// O(a²) in the active area's a entries; the rest of the state is brought up to date by
// Synchronise() in O(n²·a₀), a₀ the area's size when it was compressed. Reads of any block are
// exact meanwhile (a block outside the area costs O(a₀²)); an update or prediction touching one
// synchronises first. After Synchronise() state and covariance equal the uncompressed filter's
// (up to rounding).
class BlockEkf {
 public:
  explicit BlockEkf(int initial_capacity = 64);
  BlockEkf(const BlockEkf& other);
  BlockEkf& operator=(const BlockEkf& other);
  BlockEkf(BlockEkf&& other) noexcept;
  BlockEkf& operator=(BlockEkf&& other) noexcept;
  ~BlockEkf();

  // Registers a block kind; returns its id. Kind 0 is the pose (kPoseKind).
  int RegisterKind(const BlockKind& kind);
  const BlockKind& kind(int id) const { return kinds_[id]; }

  // Empties the state, keeping the kinds registered and the storage allocated.
  void Clear();
  // Appends a block uncorrelated with the rest (a vehicle's start pose); returns its index.
  int AddBlock(int kind, const BlockVector& mean, const BlockMatrix& cov);
  // SPEC S2, Eq. 8 (state augmentation): appends the block b = g(x_{observing}, z) with
  // covariance Σ_jk J_j P_jk J_kᵀ + J_z R J_zᵀ and cross-covariance Σ_j J_j P_j·.
  int Augment(int kind, const BlockVector& mean, std::span<const BlockJacobian> J_new_blocks,
              const BlockMatrix& J_new_z, const BlockMatrix& R);

  // SPEC S2, Eq. 2: pose block `block` moves to `moved`; P_bb ← F P_bb Fᵀ + G Q Gᵀ and the
  // block's cross-covariances ← F P_b·.
  void PredictPose(int block, const Pose2& moved, const Eigen::Matrix3d& J_x_x,
                   const ControlJacobian& J_x_u, const ControlCovariance& Q);

  // One sequential EKF update (deferred); false if S was not positive definite (nothing done).
  bool Update(const Linearisation& obs);
  // S = H P Hᵀ + R of `obs` against the current posterior; O(1) in n.
  BlockMatrix InnovationCovariance(const Linearisation& obs) const;
  // The squared Mahalanobis distance νᵀ S⁻¹ ν of `obs` (SPEC S2, Eqs. 6-7).
  double MahalanobisSquared(const Linearisation& obs) const;
  // The current covariance of 3-dim block `block` (a pose), to hoist out of a candidate loop.
  Eigen::Matrix3d PoseCovarianceOf(int block) const;
  // MahalanobisSquared() of a pose-point observation, bit for bit, without the generic
  // Linearisation (no dispatch on dimensions, no per-candidate pose block).
  double MahalanobisSquaredPosePoint(const PosePointObservation& obs) const;
  // The joint innovation covariance of several observations (a joint-compatibility test):
  // block (i, j) is H_i P H_jᵀ, plus R_i on the diagonal.
  Eigen::MatrixXd JointInnovationCovariance(std::span<const Linearisation> obs) const;
  // P₀ ← P₀ − U Uᵀ on the upper triangle, in fixed column blocks run in parallel; then the
  // kinds' normalise steps (see BlockKind), so every block is canonical when nothing is pending.
  void ApplyPendingDowndate();
  bool HasPendingDowndate() const;

  // Starts a compressed area of `active` blocks (synchronising any area before): see the class
  // comment. Blocks added later join the area.
  void Compress(std::span<const int> active);
  // The global update: every block current again, the area closed. O(n²·a₀); nothing if none.
  void Synchronise();
  bool IsCompressed() const { return area_ != nullptr; }
  // Whether block `block` is in the compressed area (every block is when none is open).
  bool IsActive(int block) const { return !area_ || InArea(block); }
  // The compressed area's state size (its blocks' entries), 0 when none is open.
  int ActiveSize() const;

  int NumBlocks() const { return static_cast<int>(blocks_.size()); }
  int BlockKindOf(int block) const { return blocks_[block].kind; }
  int BlockOffset(int block) const { return blocks_[block].offset; }
  int BlockDim(int block) const { return blocks_[block].dim; }
  int StateSize() const { return n_; }
  // Entries allocated for the state; it grows by doubling beyond this.
  int Capacity() const { return static_cast<int>(x_.size()); }
  BlockVector Mean(int block) const {
    if (area_) return CompressedMean(block);
    return x_.segment(blocks_[block].offset, blocks_[block].dim);
  }
  Pose2 PoseOf(int block) const {
    if (area_) return Pose2(Eigen::Vector3d(CompressedMean(block)));
    return Pose2(x_.segment<3>(blocks_[block].offset));
  }
  // Covariance block (a, b) of the current posterior (through any pending downdate).
  Eigen::MatrixXd CovarianceBlock(int a, int b) const;
  // CovarianceBlock(b, b) of each of `blocks`, in one pass: while an area is open, the blocks
  // outside it cost O(k·a₀²) together (one product with ψ) instead of O(a₀²) each.
  std::vector<Eigen::MatrixXd> DiagonalBlocks(std::span<const int> blocks) const;
  // The full symmetric covariance and the mean (copies; O(n²), for tests and output).
  Eigen::MatrixXd Covariance() const;
  // A filter of `blocks` alone (in that order: block i of the result is blocks[i]), with the
  // same kinds, their current means and their joint covariance: the marginal. An update that
  // touches only these blocks changes them exactly as it would in the whole filter, at O(k²) for
  // their k entries instead of O(n²). Each block at most once.
  BlockEkf Marginal(std::span<const int> blocks) const;
  Eigen::VectorXd State() const;
  // GaussianHealthProblem() of the mean and the effective covariance P₀ − U Uᵀ (a pending
  // downdate is accounted for, not applied: the check only reads). O(n²), O(n³) with `check_psd`.
  std::optional<std::string> HealthProblem(const StateHealthParams& params, bool check_psd) const;
  // The same as a NumericalError "`where`: …".
  void CheckHealth(const StateHealthParams& params, bool check_psd, std::string_view where) const;
  // Whether block `block`'s mean and covariance rows are finite: what a prediction changes. O(n).
  bool BlockFinite(int block) const;

 private:
  struct Block {
    int kind;
    int offset;
    int dim;
  };
  struct CompressedArea;  // compressed_area.hpp
  bool InArea(int block) const;
  // The compressed area's counterparts of the public reads and changes (area_ set).
  BlockVector CompressedMean(int block) const;
  Eigen::MatrixXd CompressedCovarianceBlock(int a, int b) const;
  BlockMatrix OutsideMean(int block, BlockVector* mean) const;
  BlockMatrix OutsideNormaliser(int block) const;
  Eigen::MatrixXd OutsideCovarianceBlock(int a, int b) const;
  Eigen::MatrixXd CompressedCovariance() const;
  // S = Σ H_a P_ab H_bᵀ + R through CovarianceBlock(), for observations reaching outside the area.
  BlockMatrix GenericInnovationCovariance(const Linearisation& obs) const;
  double CompressedMahalanobisSquaredPosePoint(const PosePointObservation& obs) const;
  std::optional<std::string> AreaHealthProblem(const StateHealthParams& params,
                                               bool check_psd) const;
  // `obs` with its blocks renamed to the area's filter's, if they are all active.
  std::optional<Linearisation> ToArea(const Linearisation& obs) const;
  // Synchronise()'s last part: the area's blocks written back, given C (see compressed_area.hpp).
  void WriteAreaBack(const CompressedArea& area, const Eigen::MatrixXd& C);
  // Block `block`'s bookkeeping (offset n_, angles, pose slot) without touching the storage.
  int RecordBlock(int kind);
  // The stored triangle P ← P − A Bᵀ (A Bᵀ symmetric), in fixed column blocks run in parallel.
  void SubtractFromTriangle(const Eigen::Ref<const Eigen::MatrixXd>& A,
                            const Eigen::Ref<const Eigen::MatrixXd>& B);
  // Rows [r, r+rn) × columns [c, c+cn) of the current covariance, any ranges.
  Eigen::MatrixXd CurrentRange(int r, int rn, int c, int cn) const;
  // Columns [c, c+k) of the current covariance P₀ − U Uᵀ, gathered from the stored triangle.
  Eigen::MatrixXd CurrentColumns(int c, int k) const;
  // The current columns of block `block`: cached for pose blocks while downdates are pending.
  // A view of the cache, or of `scratch` holding the gathered columns.
  Eigen::Ref<const Eigen::MatrixXd> BlockColumns(int block, Eigen::MatrixXd& scratch) const;
  // Rows [r, r+rows) × columns [c, c+cols) of the current covariance, r + rows <= c or r == c;
  // R and C are rows and cols, or Eigen::Dynamic (internal::WithDim).
  template <int R, int C>
  SmallMatrix<R, C> CurrentBlock(int r, int c, int rows, int cols) const;
  template <int R, int C>
  SmallMatrix<R, C> CurrentBlockOf(int a, int b) const;
  template <int kZ, int kD0, int kD1>
  SmallMatrix<kZ, kZ> TwoBlockS(const SmallMatrix<kD0, kD0>& P_00, int a,
                                          int b, const SmallMatrix<kZ, kD0>& J_0,
                                          const SmallMatrix<kZ, kD1>& J_1,
                                          const SmallMatrix<kZ, kZ>& R) const;
  template <int kZ>
  bool UpdateFixed(const Linearisation& obs);
  template <int kZ>
  TallMatrix<kZ> CovarianceTimesHt(const Linearisation& obs) const;
  template <int kZ>
  SmallMatrix<kZ, kZ> InnovationCovarianceFixed(const Linearisation& obs) const;
  template <int kZ>
  SmallMatrix<kZ, kZ> InnovationCovarianceFromPHt(
      const Linearisation& obs, const TallMatrix<kZ>& PHt) const;
  template <int kD>
  void CachePoseRowsOfNewBlock(int dim, std::span<const BlockJacobian> J_new_blocks);
  template <int kD>
  void AugmentFixed(const BlockVector& mean, std::span<const BlockJacobian> J_new_blocks,
                    const BlockMatrix& J_new_z, const BlockMatrix& R);
  int AppendBlock(int kind);
  void StartPoseCache();
  void Reserve(int state_size);
  void WrapAngles();
  // The kinds' normalise steps on every block that has one; needs m_ == 0. O(n) per change.
  void NormaliseBlocks();
  // b ← J b on block `block`'s rows and columns of the stored triangle (a non-pose block).
  void TransformBlockRows(int block, const BlockMatrix& J);

  std::vector<BlockKind> kinds_;
  std::vector<Block> blocks_;
  std::vector<int> pose_blocks_;    // indices into blocks_; pose_cols_ holds 3 columns each
  std::vector<int> pose_slot_;      // per block: its 3-column slot in pose_cols_, or -1
  std::vector<int> angle_indices_;  // state indices that are angles
  std::vector<int> normalised_blocks_;  // blocks whose kind has a normalise step
  int n_ = 0;
  Eigen::VectorXd x_;  // capacity-sized; the first n_ entries are the state
  Eigen::MatrixXd P_;  // capacity-sized; upper triangle of the leading n_×n_ block is valid
  Eigen::MatrixXd U_;  // capacity rows; the first m_ columns are the deferred downdate factor
  Eigen::MatrixXd pose_cols_;  // capacity × 3·poses: current pose columns while m_ > 0
  int m_ = 0;
  std::unique_ptr<CompressedArea> area_;  // while compressed
  std::unique_ptr<CompressedArea> spare_area_;  // the last area, whose storage the next reuses
};

}  // namespace slamkit
