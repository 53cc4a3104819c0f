#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/state_health.hpp"
#include "slamkit/features/corners.hpp"
#include "slamkit/features/scan_features.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/ekf_slam/active_area.hpp"
#include "slamkit/filters/features/feature_sightings.hpp"
#include "slamkit/filters/features/line_association.hpp"
#include "slamkit/filters/features/line_landmark_model.hpp"
#include "slamkit/filters/selection/selection.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {

struct FeatureEkfSlamParams {
  LineAssociationParams lines;
  // Corners: nearest neighbour on the range-bearing Mahalanobis distance (SPEC S2, Eqs. 6-7),
  // among the corners of the same kind (a concave corner never matches a convex one).
  AssociationParams corners;
  // Lines whose predicted ρ from the pose is below this are gated out (see LineLandmarkModel).
  double min_line_rho_m = 0.3;
  // Corners farther than this from the estimated pose are not candidates for association.
  double corner_reach_m = 15.0;
  // State entries allocated up front; the state grows by doubling beyond this.
  int initial_capacity = 256;
  // When the state's health is checked (see StateHealthParams): every update in Debug and
  // sanitizer builds, at output (CheckOutputHealth) in Release.
  StateHealthParams health;
  // Whether each step also runs the full update (on the matched blocks' marginal, O(k²)), for
  // the accuracy ratio of SPEC S1, Eq. 24 in LastSelectionStats() (see
  // EkfSlamParams::selection_diagnostics).
  bool selection_diagnostics = false;
  // kCompressed: each scan's updates touch the active area only (Guivant & Nebot 2001; see
  // EkfSlamParams::update): the lines whose seen extent and the corners whose estimate lie
  // within the area's radius. The result equals the dense filter's after each global update.
  EkfUpdateMode update = EkfUpdateMode::kDense;
  ActiveAreaParams active_area;  // with kCompressed
  // With kCompressed: how far from the robot its features are seen (the extractor's usable
  // range), which sets the area's radius. A feature beyond it is still exact: its update brings
  // the whole state up to date first.
  double area_reach_m = 20.0;
};

// What Update() decided for each line and corner of the scan (landmark: the line or corner
// index, also for the new ones; -1 when dropped).
struct FeatureDecisions {
  std::vector<AssociationDecision> lines;
  std::vector<AssociationDecision> corners;
};

// EKF-SLAM with line and corner landmarks (SPEC S1): a BlockEkf holding one pose, lines of the
// line kind (LineLandmarkModel; extents in a LineMap) and corners of a point kind, and a per-scan
// UpdatePipeline over two kinds, LineSightings and CornerSightings: line association
// (LineAssociator), corner association (an Associator, by default nearest neighbour, offered only
// corners of the sighting's kind), one selection step (a SelectionPolicy) over the matched lines
// and corners together, the sequential updates, then augmentation by the new features. Corners
// are point landmarks observed in range-bearing (CornerRangeBearing): PointLandmarkModel over a
// RangeBearingModel is their model unchanged.
//
// (EkfSlam is the point-landmark filter behind LandmarkSlamFilter; its observations are
// PointObservations, so the line kind, whose sightings carry segments, gets this filter of its
// own built from the same parts rather than a second, differently typed input there.)
class FeatureEkfSlam {
 public:
  // `selection` defaults to SelectAll, `corner_associator` to NearestNeighbourAssociator.
  FeatureEkfSlam(const FeatureEkfSlamParams& params, std::unique_ptr<MotionModel> motion,
                 std::unique_ptr<SelectionPolicy> selection = {},
                 std::unique_ptr<Associator> corner_associator = {});
  // The corner model points at corner_sensor_: not copyable (nor, hence, movable).
  FeatureEkfSlam(const FeatureEkfSlam&) = delete;
  FeatureEkfSlam& operator=(const FeatureEkfSlam&) = delete;

  void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov = Eigen::Matrix3d::Zero());
  // SPEC S2, Eq. 2: moves the pose with control `u` (noise: `control_noise` or the model's).
  void Predict(const Control& u, double dt_s, const ControlCovariance* control_noise = nullptr);
  // One scan's features in the robot frame (ToRobotFrame): association, selection, sequential
  // updates and augmentation (SPEC S1 items 1-3); then two line landmarks of one wall that the
  // scan's extents made meet are fused (FuseMetLines in the source). Throws
  // std::invalid_argument on a non-finite feature (before any change).
  // With health.every_update(), NumericalError if the resulting state is not healthy.
  FeatureDecisions Update(const ScanFeatures& robot_frame);
  // The full check (finite, symmetric, PSD) unless health.mode is kOff; NumericalError if it fails.
  void CheckOutputHealth() const;

  Pose2 pose() const { return ekf_.PoseOf(kPoseBlock); }
  Eigen::Matrix3d PoseCovariance() const { return ekf_.CovarianceBlock(kPoseBlock, kPoseBlock); }
  // Line landmarks ever started, including those merged into another (see LineMergedInto).
  int NumLines() const { return lines_.size(); }
  // Line landmarks of their own: one per wall.
  int NumActiveLines() const;
  // The line `line` was fused with and merged into (same wall, see Update()), or -1.
  int LineMergedInto(int line) const { return lines_.MergedInto(line); }
  PolarLine Line(int line) const { return LineOf(ekf_.Mean(lines_.Block(line))); }
  Eigen::Matrix2d LineCovariance(int line) const;
  const LineExtent& LineExtentOf(int line) const { return lines_.Extent(line); }
  int NumCorners() const { return corners_.size(); }
  Eigen::Vector2d CornerPosition(int corner) const { return ekf_.Mean(corners_.Block(corner)); }
  CornerKind CornerKindOf(int corner) const { return corners_.Kind(corner); }
  const BlockEkf& ekf() const { return ekf_; }
  // The global update of compressed updates (nothing with dense ones): every block current, so
  // that reads of the whole map (output) cost no more than the dense filter's.
  void Synchronise() { area_.Synchronise(ekf_); }
  // What compressed updates cost so far (zeros with dense ones).
  const CompressionStats& Compression() const { return area_.stats(); }
  // What the selection policy did in the last Update().
  const SelectionStats& LastSelectionStats() const { return selection_stats_; }
  // Turns FeatureEkfSlamParams::selection_diagnostics on or off from the next Update() (a run
  // may take the ratio on a sample of its steps).
  void SetSelectionDiagnostics(bool on) { params_.selection_diagnostics = on; }

 private:
  static constexpr int kPoseBlock = 0;
  void MaintainArea();
  // `lines`: the decisions on the scan's lines.
  void ExtendMatchedLines(const ScanFeatures& scan, const std::vector<AssociationDecision>& lines);
  Linearisation SameLine(int i, int j) const;
  bool NearlySameLine(const PolarLine& a, const LineExtent& ea, const PolarLine& b,
                      const LineExtent& eb) const;
  void FuseMetLines(const std::vector<AssociationDecision>& lines);

  FeatureEkfSlamParams params_;
  std::unique_ptr<MotionModel> motion_;
  std::unique_ptr<SelectionPolicy> selection_;
  std::unique_ptr<Associator> corner_associator_;
  LineAssociator line_associator_;
  RangeBearingModel corner_sensor_;
  BlockEkf ekf_;
  int line_kind_ = -1;
  int corner_kind_ = -1;
  LineLandmarkModel line_model_;
  PointLandmarkModel corner_model_;
  LineMap lines_;
  CornerMap corners_;
  ActiveArea area_;
  SelectionStats selection_stats_;
  long updates_ = 0;  // since Reset(), to name the step a health check failed at
};

}  // namespace slamkit
