#include "slamkit/filters/ekf_slam/ekf_slam.hpp"

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
      fej_model_(*sensor_),
      area_(params.active_area) {
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
  landmarks_.Clear();
  area_.Reset();
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

const ObservationModel& EkfSlam::UpdateModel() const {
  if (params_.jacobians == JacobianEstimates::kFirstEstimates) return fej_model_;
  return point_model_;
}

double EkfSlam::MahalanobisDistance(int landmark, const PointObservation& obs) const {
  return PosePointDistance(ekf_, point_model_, kPoseBlock, BlockOf(landmark), obs, pose(),
                           ekf_.PoseCovarianceOf(kPoseBlock));
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
  const int index = AddPointLandmark(ekf_, point_model_, landmarks_, kPoseBlock, obs);
  fej_model_.Record(BlockOf(index), LandmarkPosition(index));  // Huang et al. 2008, Sec. IV
  unchecked_ = true;
  return index;
}

// SPEC S2 / S1 items 1-3: association, selection and the sequential updates of the matched
// observations, then augmentation by the new ones. The landmarks it names are taken for the rest
// of the scan.
void EkfSlam::RunPipeline(std::span<const PointObservation> part, std::vector<char>& taken,
                          std::vector<AssociationDecision>& decisions) {
  const int before = NumLandmarks();
  PointSightings points({&point_model_, &UpdateModel(), associator_.get()}, landmarks_, part,
                        taken);
  LandmarkSightings* const kinds[] = {&points};
  UpdatePipeline pipeline(ekf_, kPoseBlock, kinds);
  const SelectionStats stats = pipeline.Run(*selection_, params_.selection_diagnostics);
  // A part with nothing matched had no selection step to account for.
  if (stats.candidates > 0) selection_stats_.Add(stats);
  // Huang et al. 2008, Sec. IV: each new landmark's first estimate, its initialised mean.
  for (int l = before; l < NumLandmarks(); ++l) fej_model_.Record(BlockOf(l), LandmarkPosition(l));
  const std::vector<AssociationDecision>& decided = pipeline.Decisions(0);
  MarkTaken(decided, taken);
  decisions.insert(decisions.end(), decided.begin(), decided.end());
}

std::vector<AssociationDecision> EkfSlam::Update(std::span<const PointObservation> observations) {
  CheckFinite(observations);
  selection_stats_ = {};
  std::vector<AssociationDecision> decisions;
  decisions.reserve(observations.size());
  // A landmark takes at most one sighting per scan: two sightings are two landmarks.
  std::vector<char> taken(NumLandmarks() + observations.size(), 0);
  if (params_.update == EkfUpdateMode::kCompressed) {
    area_.Maintain(ekf_, kPoseBlock, landmarks_.Blocks(), sensor_->MaxRange());
  }
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

std::vector<FilterCounter> EkfSlam::Counters() const {
  if (params_.update != EkfUpdateMode::kCompressed) return {};
  const CompressionStats& s = area_.stats();
  return {{"global_updates", double(s.global_updates)},
          {"global_update_s", s.global_update_s},
          {"max_active_size", double(s.max_active_size)}};
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
  // One pass over the covariance blocks: cheaper through an open compressed area.
  std::vector<int> blocks(NumLandmarks());
  for (int i = 0; i < NumLandmarks(); ++i) blocks[i] = BlockOf(i);
  const std::vector<Eigen::MatrixXd> covariances = ekf_.DiagonalBlocks(blocks);
  for (int i = 0; i < NumLandmarks(); ++i) {
    map.landmarks.push_back({LandmarkSourceId(i), LandmarkPosition(i), covariances[i]});
  }
  return map;
}

}  // namespace slamkit
