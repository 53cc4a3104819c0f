#include "slamkit/filters/features/feature_ekf_slam.hpp"

#include "slamkit/features/line_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slamkit {
namespace {

const BlockKind kCornerKind{2, {}, false, nullptr};
// Of the pseudo-observation that fuses two line landmarks: (0.1 mm)², (0.1 mrad)².
constexpr double kSameLineVariance = 1e-8;

RangeBearingParams CornerSensorParams(const FeatureEkfSlamParams& params) {
  RangeBearingParams p;
  p.max_range_m = params.corner_reach_m;
  return p;
}

void CheckFinite(const ScanFeatures& scan) {
  for (const LineSegment& s : scan.lines) {
    if (!std::isfinite(s.line.rho_m) || !std::isfinite(s.line.alpha_rad) ||
        !s.covariance.allFinite() || !s.start_m.allFinite() || !s.end_m.allFinite()) {
      throw std::invalid_argument("FeatureEkfSlam::Update: line with a non-finite value");
    }
  }
  for (const Corner& c : scan.corners) {
    if (!c.point_m.allFinite() || !c.covariance.allFinite()) {
      throw std::invalid_argument("FeatureEkfSlam::Update: corner with a non-finite value");
    }
  }
}

}  // namespace

FeatureEkfSlam::FeatureEkfSlam(const FeatureEkfSlamParams& params,
                               std::unique_ptr<MotionModel> motion,
                               std::unique_ptr<SelectionPolicy> selection,
                               std::unique_ptr<Associator> corner_associator)
    : params_(params),
      motion_(std::move(motion)),
      selection_(selection ? std::move(selection) : std::make_unique<SelectAll>()),
      corner_associator_(corner_associator
                             ? std::move(corner_associator)
                             : std::make_unique<NearestNeighbourAssociator>(params.corners)),
      line_associator_(params.lines),
      corner_sensor_(CornerSensorParams(params)),
      ekf_(params.initial_capacity),
      line_kind_(ekf_.RegisterKind(LineBlockKind())),
      corner_kind_(ekf_.RegisterKind(kCornerKind)),
      line_model_(line_kind_, params.min_line_rho_m),
      corner_model_(corner_sensor_, corner_kind_, 0.0),
      area_(params.active_area) {
  if (params.update == EkfUpdateMode::kCompressed && !(params.area_reach_m > 0.0)) {
    throw std::invalid_argument("FeatureEkfSlam: compressed updates need area_reach_m > 0");
  }
  Reset(Pose2());
}

void FeatureEkfSlam::Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) {
  ekf_.Clear();
  ekf_.AddBlock(kPoseKind, pose.vector(), pose_cov);
  lines_.Clear();
  corners_.Clear();
  area_.Reset();
  selection_stats_ = {};
  updates_ = 0;
}

// SPEC S2, Eq. 2 (Probabilistic Robotics Table 10.1).
void FeatureEkfSlam::Predict(const Control& u, double dt_s,
                             const ControlCovariance* control_noise) {
  if (!u.allFinite() || !std::isfinite(dt_s) || (control_noise && !control_noise->allFinite())) {
    throw std::invalid_argument("FeatureEkfSlam::Predict: non-finite control, time step or noise");
  }
  Eigen::Matrix3d J_x_x;
  ControlJacobian J_x_u;
  const Pose2 moved = motion_->Move(pose(), u, dt_s, &J_x_x, &J_x_u);
  const ControlCovariance Q = control_noise ? *control_noise : motion_->Noise(u, dt_s);
  ekf_.PredictPose(kPoseBlock, moved, J_x_x, J_x_u, Q);
}

Eigen::Matrix2d FeatureEkfSlam::LineCovariance(int line) const {
  const int b = lines_.Block(line);
  return ekf_.CovarianceBlock(b, b);
}

// SPEC S1: both kinds are associated against the prior, then offered to the selection policy
// together, so it ranks lines and corners on the same footing; new features are added after.
FeatureDecisions FeatureEkfSlam::Update(const ScanFeatures& robot_frame) {
  CheckFinite(robot_frame);
  if (params_.update == EkfUpdateMode::kCompressed) MaintainArea();
  LineSightings lines(line_associator_, line_model_, lines_, robot_frame.lines);
  CornerSightings corners(corner_model_, *corner_associator_, corners_, robot_frame.corners);
  LandmarkSightings* const kinds[] = {&lines, &corners};  // lines first: the selection's order
  UpdatePipeline pipeline(ekf_, kPoseBlock, kinds);
  pipeline.Associate();
  selection_stats_ = pipeline.SelectAndUpdate(*selection_, params_.selection_diagnostics);
  ekf_.ApplyPendingDowndate();  // also brings the lines back to ρ ≥ 0
  ExtendMatchedLines(robot_frame, pipeline.Decisions(0));
  FuseMetLines(pipeline.Decisions(0));
  pipeline.Augment();
  ++updates_;
  if (params_.health.every_update()) {
    const bool psd = params_.health.PsdDue(updates_, ekf_.StateSize());
    ekf_.CheckHealth(params_.health, psd,
                     "FeatureEkfSlam after update " + std::to_string(updates_));
  }
  return {pipeline.Decisions(0), pipeline.Decisions(1)};
}

// Guivant & Nebot 2001 with SPEC S1's landmarks: a line is as far as the nearest point of its
// seen extent (an infinite line passes near every area), a corner as its estimate. Merged lines
// take no more updates and stay out.
void FeatureEkfSlam::MaintainArea() {
  std::vector<int> blocks;
  std::vector<int> line_of_block(ekf_.NumBlocks(), -1);
  for (int i = 0; i < lines_.size(); ++i) {
    if (!lines_.Active(i)) continue;
    blocks.push_back(lines_.Block(i));
    line_of_block[lines_.Block(i)] = i;
  }
  for (int c = 0; c < corners_.size(); ++c) blocks.push_back(corners_.Block(c));
  // A sighting matches a line whose extent it overlaps within overlap_margin_m, and a corner
  // within corner_reach_m: the reach covers both, so association needs the area alone.
  const double reach_m = std::max(params_.area_reach_m + params_.lines.overlap_margin_m,
                                  params_.corner_reach_m);
  area_.Maintain(ekf_, kPoseBlock, blocks, reach_m,
                 [this, &line_of_block](int b, const Eigen::Vector2d& p) {
                   const int line = line_of_block[b];
                   if (line < 0) return (ekf_.Mean(b) - p).squaredNorm();
                   const LineExtent& e = lines_.Extent(line);
                   return PointSegmentDistanceSq(p, e.start_m, e.end_m);
                 });
}

void FeatureEkfSlam::CheckOutputHealth() const {
  if (params_.health.enabled()) ekf_.CheckHealth(params_.health, true, "FeatureEkfSlam at output");
}

// A matched sighting is that wall: its segment, placed from the updated pose, grows the extent
// (whether or not the selection applied it).
void FeatureEkfSlam::ExtendMatchedLines(const ScanFeatures& scan,
                                        const std::vector<AssociationDecision>& lines) {
  const Pose2 x = pose();
  for (std::size_t i = 0; i < scan.lines.size(); ++i) {
    if (lines[i].kind != AssociationDecision::Kind::kMatched) continue;
    const int line = lines[i].landmark;
    lines_.Extend(line, Line(line), x.TransformFrom(scan.lines[i].start_m),
                  x.TransformFrom(scan.lines[i].end_m));
  }
}

int FeatureEkfSlam::NumActiveLines() const {
  int n = 0;
  for (int i = 0; i < lines_.size(); ++i) n += lines_.Active(i);
  return n;
}

// The pseudo-observation l_i − l_j = 0 of two line landmarks (H = [I, −I], a tiny R).
Linearisation FeatureEkfSlam::SameLine(int i, int j) const {
  const PolarLine a = Line(i), b = Line(j);
  Linearisation c;
  c.innovation = -LineInnovation(a, b);
  c.H.Add(lines_.Block(i), BlockMatrix::Identity(2, 2));
  c.H.Add(lines_.Block(j), -BlockMatrix::Identity(2, 2));
  c.R = BlockMatrix::Identity(2, 2) * kSameLineVariance;
  return c;
}

// Whether lines `a` and `b` (with their seen extents) are one wall by their own geometry: the
// angle between them and each extent's distance from the other's line within the separation
// under which association would not start a second landmark (new_min_separation_*). The χ² test
// alone is not enough: two parallel walls a metre apart pass it while the filter is uncertain,
// and the fusion's hard constraint would then drag the map and the pose onto one of them.
bool FeatureEkfSlam::NearlySameLine(const PolarLine& a, const LineExtent& ea, const PolarLine& b,
                                    const LineExtent& eb) const {
  const double max_rho = params_.lines.new_min_separation_rho_m;
  if (std::abs(WrapAngle(a.alpha_rad - b.alpha_rad)) > params_.lines.new_min_separation_alpha_rad) {
    return false;
  }
  for (const Eigen::Vector2d& p : {eb.start_m, eb.end_m}) {
    if (std::abs(DistanceToLine(a, p)) > max_rho) return false;
  }
  for (const Eigen::Vector2d& p : {ea.start_m, ea.end_m}) {
    if (std::abs(DistanceToLine(b, p)) > max_rho) return false;
  }
  return true;
}

// Two landmarks started from glimpses of one wall that did not overlap (seen through two doors)
// meet once its extent has grown: a landmark matched in this scan whose extent now overlaps
// another's, with (ρ, α) compatible (l_i − l_j within the χ² gate of its covariance), is fused
// with it by the pseudo-observation l_i − l_j = 0, and the later of the two is merged into the
// earlier. (The merged block stays in the state, tied to the other: BlockEkf removes no block.)
void FeatureEkfSlam::FuseMetLines(const std::vector<AssociationDecision>& lines) {
  for (const AssociationDecision& m : lines) {
    if (m.kind != AssociationDecision::Kind::kMatched || !lines_.Active(m.landmark)) continue;
    int i = m.landmark;
    for (int j = 0; j < lines_.size(); ++j) {
      if (j == i || !lines_.Active(j)) continue;
      const LineExtent &a = lines_.Extent(i), &b = lines_.Extent(j);
      const PolarLine l = Line(i);
      // The tests that need no read of line j first (O(a) outside a compressed area): the
      // overlap, and j's extent near line i (which NearlySameLine also requires).
      const double max_rho = params_.lines.new_min_separation_rho_m;
      if (SegmentOverlapM(a.start_m, a.end_m, b.start_m, b.end_m, l.alpha_rad) <= 0.0 ||
          std::abs(DistanceToLine(l, b.start_m)) > max_rho ||
          std::abs(DistanceToLine(l, b.end_m)) > max_rho || !NearlySameLine(l, a, Line(j), b)) {
        continue;
      }
      const Linearisation c = SameLine(i, j);
      if (ekf_.MahalanobisSquared(c) >= params_.lines.gate_chi2) continue;
      ekf_.Update(c);
      ekf_.ApplyPendingDowndate();
      const int into = std::min(i, j);
      lines_.Merge(std::max(i, j), into, Line(into));
      i = into;
    }
  }
}

}  // namespace slamkit
