#include "slamkit/filters/ekf/ekf_slam.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace slamkit {
namespace {

void CheckFinite(std::span<const PointObservation> observations) {
  for (const PointObservation& obs : observations) {
    if (!obs.z.allFinite() || !obs.R.allFinite()) {
      throw std::invalid_argument("EkfSlam::Update: observation with a non-finite value");
    }
  }
}

void CheckFinite(const Control& u, double dt_s, const ControlCovariance* control_noise) {
  if (!u.allFinite() || !std::isfinite(dt_s) || (control_noise && !control_noise->allFinite())) {
    throw std::invalid_argument("EkfSlam::Predict: non-finite control, time step or noise");
  }
}

int Capacity(const EkfSlamParams& params) {
  return 3 + 2 * std::max(params.initial_landmark_capacity, 1);
}

const BlockKind kPointKind{2, {}, false};

}  // namespace

std::unique_ptr<Associator> MakeAssociator(const EkfSlamParams& params) {
  switch (params.association_method) {
    case AssociationMethod::kKnown: return std::make_unique<KnownAssociation>();
    case AssociationMethod::kJointCompatibility:
      return std::make_unique<JcbbAssociator>(params.association, params.jcbb);
    case AssociationMethod::kMaximumLikelihood:
      return std::make_unique<MaximumLikelihoodAssociator>(params.association);
    case AssociationMethod::kGlobalNearestNeighbour:
      return std::make_unique<GlobalNearestNeighbourAssociator>(params.association);
    case AssociationMethod::kNearestNeighbour: break;
  }
  return std::make_unique<NearestNeighbourAssociator>(params.association);
}

// A part of a scan (all of it, or one observation) against the filter's current posterior.
// Landmarks taken earlier in the scan are no candidates.
class EkfSlam::ScanContext final : public AssociationContext {
 public:
  // The posterior does not change while the associator runs: the pose, its covariance and the
  // reach gate are computed here once for all observations and candidates.
  ScanContext(const EkfSlam& slam, std::span<const PointObservation> observations,
              const std::vector<char>& taken)
      : slam_(slam),
        observations_(observations),
        taken_(taken),
        pose_(slam.pose()),
        P_pose_(slam.ekf_.PoseCovarianceOf(kPoseBlock)),
        gate_(slam.point_model_.GateFrom(pose_)) {}

  int NumObservations() const override { return static_cast<int>(observations_.size()); }
  const PointObservation& Observation(int i) const override { return observations_[i]; }
  int NumLandmarks() const override { return slam_.NumLandmarks(); }
  std::span<const AssociationCandidate> Candidates(int i) const override {
    std::vector<AssociationCandidate>& candidates = slam_.candidate_scratch_;
    candidates.clear();
    for (int l = 0; l < slam_.NumLandmarks(); ++l) {
      if (taken_[l] || !gate_.Passes(slam_.LandmarkPosition(l))) continue;
      candidates.push_back({l, Distance(i, l)});
    }
    return candidates;
  }
  int LandmarkWithSourceId(LandmarkId id) const override {
    const auto it = slam_.index_of_id_.find(id);
    return it == slam_.index_of_id_.end() ? -1 : it->second;
  }
  double Distance(int i, int landmark) const override {
    return slam_.PointDistance(landmark, observations_[i], pose_, P_pose_);
  }
  JointInnovation Joint(std::span<const Pairing> hypothesis) const override {
    std::vector<Linearisation> parts;
    JointInnovation joint;
    for (const Pairing& p : hypothesis) {
      parts.push_back(slam_.LinearisePoint(p.landmark, observations_[p.observation]));
    }
    joint.nu.resize(2 * static_cast<int>(parts.size()));
    for (std::size_t k = 0; k < parts.size(); ++k) joint.nu.segment<2>(2 * k) = parts[k].innovation;
    joint.S = slam_.ekf_.JointInnovationCovariance(parts);
    return joint;
  }

 private:
  const EkfSlam& slam_;
  std::span<const PointObservation> observations_;
  const std::vector<char>& taken_;
  Pose2 pose_;
  Eigen::Matrix3d P_pose_;
  PointLandmarkModel::ReachGate gate_;
};

EkfSlam::EkfSlam(const EkfSlamParams& params, std::unique_ptr<MotionModel> motion,
                 std::unique_ptr<PointSensorModel> sensor, std::unique_ptr<Associator> associator,
                 std::unique_ptr<SelectionPolicy> selection)
    : params_(params),
      motion_(std::move(motion)),
      sensor_(std::move(sensor)),
      associator_(associator ? std::move(associator) : MakeAssociator(params)),
      selection_(selection ? std::move(selection) : std::make_unique<SelectAll>()),
      ekf_(0),  // Reset() allocates the state at its capacity
      point_kind_(ekf_.RegisterKind(kPointKind)),
      point_model_(*sensor_, point_kind_, params.association_margin_m),
      fej_model_(*sensor_) {
  Reset(Pose2());
}

void EkfSlam::Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) {
  // Reusing the storage keeps a long-lived filter in memory it has touched already.
  if (ekf_.Capacity() == Capacity(params_)) {
    ekf_.Clear();
  } else {
    ekf_ = BlockEkf(Capacity(params_));
    point_kind_ = ekf_.RegisterKind(kPointKind);
  }
  ekf_.AddBlock(kPoseKind, pose.vector(), pose_cov);
  fej_model_.Clear();
  fej_model_.SetPriorPose(pose);
  landmark_blocks_.clear();
  source_ids_.clear();
  index_of_id_.clear();
  predictions_ = 0;
  updates_ = 0;
  health_checks_ = 0;
  unchecked_ = true;
  selection_stats_ = {};
}

// SPEC S2, Eq. 2 (Probabilistic Robotics Table 10.1).
void EkfSlam::Predict(const Control& u, double dt_s, const ControlCovariance* control_noise) {
  CheckFinite(u, dt_s, control_noise);
  Eigen::Matrix3d J_x_x;
  ControlJacobian J_x_u;
  const Pose2 moved = motion_->Move(pose(), u, dt_s, &J_x_x, &J_x_u);
  if (params_.jacobians == JacobianEstimates::kFirstEstimates) {
    FirstEstimatesMotionJacobian(moved, fej_model_.prior_pose(), &J_x_x);
  }
  fej_model_.SetPriorPose(moved);
  const ControlCovariance Q = control_noise ? *control_noise : motion_->Noise(u, dt_s);
  ekf_.PredictPose(kPoseBlock, moved, J_x_x, J_x_u, Q);
  ++predictions_;
  // Only what the prediction changed, the pose's mean and covariance rows, and only their
  // finiteness (O(n): this runs at every step); the PSD test waits for the next update's check.
  if (params_.health.every_update() && !ekf_.BlockFinite(kPoseBlock)) {
    ThrowNumericalError(HealthWhere(HealthStep::kPrediction),
                        ekf_.HealthProblem(params_.health, false).value_or(""));
  }
}

Linearisation EkfSlam::LinearisePoint(int landmark, const PointObservation& obs) const {
  const int blocks[] = {kPoseBlock, BlockOf(landmark)};
  return Linearise(point_model_, ekf_, blocks, obs.z, obs.R);
}

const ObservationModel& EkfSlam::UpdateModel() const {
  if (params_.jacobians == JacobianEstimates::kFirstEstimates) return fej_model_;
  return point_model_;
}

MatchedObservation EkfSlam::Matched(int landmark, const PointObservation& obs) const {
  MatchedObservation m{&UpdateModel(), {kPoseBlock, BlockOf(landmark)}, 2, obs.z, obs.R};
  return m;
}

double EkfSlam::MahalanobisDistance(int landmark, const PointObservation& obs) const {
  return PointDistance(landmark, obs, pose(), ekf_.PoseCovarianceOf(kPoseBlock));
}

// The generic MahalanobisSquared(LinearisePoint()) at fixed sizes, with the pose and its
// covariance supplied by the caller (association hoists them out of its candidate loop).
double EkfSlam::PointDistance(int landmark, const PointObservation& obs, const Pose2& x,
                              const Eigen::Matrix3d& P_pose) const {
  PosePointObservation o;
  o.pose = kPoseBlock;
  o.point = BlockOf(landmark);
  o.R = &obs.R;
  o.P_pose = &P_pose;
  point_model_.LinearisePosePoint(x, LandmarkPosition(landmark), obs.z, o);
  return ekf_.MahalanobisSquaredPosePoint(o);
}

// With kFirstEstimates, H from FirstEstimatesPointModel (Huang, Mourikis, Roumeliotis 2008,
// Sec. IV); the innovation always from the current means.
Linearisation EkfSlam::UpdateLinearisation(int landmark, const PointObservation& obs) const {
  const int blocks[] = {kPoseBlock, BlockOf(landmark)};
  return Linearise(UpdateModel(), ekf_, blocks, obs.z, obs.R);
}

// SPEC S1 item 1 (Probabilistic Robotics Table 10.2, one innovation at a time).
void EkfSlam::UpdateLandmark(int landmark, const PointObservation& obs) {
  ekf_.Update(UpdateLinearisation(landmark, obs));
  unchecked_ = true;
}

// SPEC S2, Eq. 8.
int EkfSlam::AddLandmark(const PointObservation& obs) {
  const int observers[] = {kPoseBlock};
  const int block = AugmentFrom(point_model_, ekf_, observers, obs.z, obs.R);
  fej_model_.Record(block, ekf_.Mean(block));  // Huang et al. 2008, Sec. IV: its first estimate
  unchecked_ = true;
  const int index = NumLandmarks();
  landmark_blocks_.push_back(block);
  source_ids_.push_back(obs.id);
  if (obs.id != kNoLandmark) index_of_id_.emplace(obs.id, index);
  return index;
}

// SPEC S1 items 1 and 3: the selection policy chooses which matched observations update the
// filter, and in what order, from their S, H and R against the current posterior.
void EkfSlam::SelectAndUpdate(std::span<const PointObservation> part,
                              const std::vector<AssociationDecision>& decided) {
  std::vector<MatchedObservation> matched;
  for (std::size_t i = 0; i < part.size(); ++i) {
    if (decided[i].kind == AssociationDecision::Kind::kMatched) {
      matched.push_back(Matched(decided[i].landmark, part[i]));
    }
  }
  if (matched.empty()) return;
  BlockSelectionSession session(ekf_, std::move(matched), params_.selection_diagnostics);
  selection_->Select(session);
  selection_stats_.Add(session.stats());
}

// SPEC S2, Eq. 8 for every observation association called new; all landmarks it names are
// taken for the rest of the scan.
void EkfSlam::AugmentNew(std::span<const PointObservation> part,
                         std::vector<AssociationDecision> decided, std::vector<char>& taken,
                         std::vector<AssociationDecision>& decisions) {
  for (std::size_t i = 0; i < part.size(); ++i) {
    AssociationDecision& d = decided[i];
    if (d.kind == AssociationDecision::Kind::kNew) d.landmark = AddLandmark(part[i]);
    if (d.landmark >= 0) {
      taken.resize(std::max<std::size_t>(taken.size(), d.landmark + 1), 0);
      taken[d.landmark] = 1;
    }
    decisions.push_back(d);
  }
}

// Association, then selection and the sequential updates of the matched observations, then
// augmentation by the new ones.
void EkfSlam::RunPipeline(std::span<const PointObservation> part, std::vector<char>& taken,
                          std::vector<AssociationDecision>& decisions) {
  std::vector<AssociationDecision> decided =
      associator_->Associate(ScanContext(*this, part, taken));
  SelectAndUpdate(part, decided);
  AugmentNew(part, std::move(decided), taken, decisions);
}

std::vector<AssociationDecision> EkfSlam::Update(std::span<const PointObservation> observations) {
  CheckFinite(observations);
  selection_stats_ = {};
  std::vector<AssociationDecision> decisions;
  decisions.reserve(observations.size());
  // A landmark takes at most one sighting per scan: two sightings are two landmarks.
  std::vector<char> taken(NumLandmarks() + observations.size(), 0);
  const int n = static_cast<int>(observations.size());
  if (params_.schedule == UpdateSchedule::kPerScan ||
      params_.association_method == AssociationMethod::kJointCompatibility ||
      params_.association_method == AssociationMethod::kGlobalNearestNeighbour) {
    RunPipeline(observations, taken, decisions);
  } else {
    for (int i = 0; i < n; ++i) RunPipeline(observations.subspan(i, 1), taken, decisions);
  }
  ekf_.ApplyPendingDowndate();
  ++updates_;
  // A scan without sightings changes nothing, unless UpdateLandmark() or AddLandmark() ran
  // before it (what a prediction changes is checked there).
  if (params_.health.every_update() && (!observations.empty() || unchecked_)) {
    unchecked_ = false;
    ++health_checks_;
    const bool psd = params_.health.PsdDue(health_checks_, StateSize());
    if (auto problem = ekf_.HealthProblem(params_.health, psd)) {
      ThrowNumericalError(HealthWhere(HealthStep::kUpdate), *problem);
    }
  }
  return decisions;
}

void EkfSlam::CheckOutputHealth() const {
  if (params_.health.enabled()) {
    ekf_.CheckHealth(params_.health, true, HealthWhere(HealthStep::kOutput));
  }
}

std::string EkfSlam::HealthWhere(HealthStep step) const {
  std::ostringstream s;
  s << "EkfSlam ";
  const int landmarks = NumLandmarks();
  switch (step) {
    case HealthStep::kUpdate:
      s << "after update " << updates_ << " (prediction " << predictions_ << ", ";
      break;
    case HealthStep::kPrediction:
      s << "after prediction " << predictions_ << " (update " << updates_ << ", ";
      break;
    case HealthStep::kOutput:
      s << "at output (update " << updates_ << ", prediction " << predictions_ << ", ";
      break;
  }
  s << landmarks << " landmarks)";
  return s.str();
}

Eigen::Matrix3d EkfSlam::PoseCovariance() const {
  return ekf_.CovarianceBlock(kPoseBlock, kPoseBlock);
}

Eigen::Matrix2d EkfSlam::LandmarkCovariance(int a, int b) const {
  return ekf_.CovarianceBlock(BlockOf(a), BlockOf(b));
}

LandmarkMap EkfSlam::Map() const {
  LandmarkMap map;
  map.landmarks.reserve(NumLandmarks());
  for (int i = 0; i < NumLandmarks(); ++i) {
    map.landmarks.push_back({source_ids_[i], LandmarkPosition(i), LandmarkCovariance(i)});
  }
  return map;
}

}  // namespace slamkit
