// SPEC S3: cooperative EKF-SLAM over a fleet, in the three modes of CooperativeMode.
#include "slamkit/filters/cooperative/cooperative_ekf_slam.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/state_health.hpp"
#include "slamkit/models/extended_observation.hpp"

namespace slamkit {
namespace {

const BlockKind kCooperativePointKind{2, {}, false};

void CheckScan(const FleetScan& scan, int vehicles) {
  if (scan.vehicle < 0 || scan.vehicle >= vehicles || !std::isfinite(scan.t_s)) {
    throw std::invalid_argument("CooperativeEkfSlam::Update: no such vehicle, or a non-finite time");
  }
  for (const PointObservation& obs : scan.landmarks) {
    if (!obs.z.allFinite() || !obs.R.allFinite()) {
      throw std::invalid_argument("CooperativeEkfSlam::Update: a non-finite landmark sighting");
    }
  }
  for (const VehicleObservation& obs : scan.vehicles) {
    if (obs.target < 0 || obs.target >= vehicles || obs.target == scan.vehicle ||
        !obs.z.allFinite() || !obs.R.allFinite()) {
      throw std::invalid_argument("CooperativeEkfSlam::Update: a bad vehicle sighting");
    }
  }
}

}  // namespace

CooperativeEkfSlam::CooperativeEkfSlam(const CooperativeEkfSlamParams& params, int vehicles,
                                       int self, std::unique_ptr<MotionModel> motion,
                                       std::unique_ptr<PointSensorModel> sensor,
                                       std::unique_ptr<Associator> associator,
                                       std::unique_ptr<SelectionPolicy> selection)
    : params_(params),
      vehicles_(vehicles),
      self_(self),
      motion_(std::move(motion)),
      sensor_(std::move(sensor)),
      associator_(associator ? std::move(associator) : MakeAssociator(params.ekf)),
      selection_(selection ? std::move(selection) : std::make_unique<SelectAll>()),
      ekf_(0),
      point_kind_(ekf_.RegisterKind(kCooperativePointKind)),
      point_model_(*sensor_, point_kind_, params.ekf.association_margin_m),
      fej_models_(std::max(vehicles, 0), FirstEstimatesPointModel(*sensor_)),
      block_of_(vehicles, -1),
      latest_(vehicles) {
  if (vehicles < 1 || self < -1 || self >= vehicles) {
    throw std::invalid_argument("CooperativeEkfSlam: needs a vehicle, and self among them or -1");
  }
  if (self < 0 && params.mode != CooperativeMode::kExact) {
    throw std::invalid_argument("CooperativeEkfSlam: the centralised filter (self -1) is kExact");
  }
  int blocks = 0;
  for (int v = 0; v < vehicles; ++v) {
    if (params.mode != CooperativeMode::kMono || v == self) block_of_[v] = blocks++;
  }
}

void CooperativeEkfSlam::Reset(std::span<const Pose2> start_poses,
                               const Eigen::Matrix3d& pose_cov) {
  if (static_cast<int>(start_poses.size()) != vehicles_) {
    throw std::invalid_argument("CooperativeEkfSlam::Reset: one start pose per vehicle");
  }
  const int tracked = static_cast<int>(std::count_if(block_of_.begin(), block_of_.end(),
                                                     [](int b) { return b >= 0; }));
  ekf_ = BlockEkf(3 * tracked + 2 * std::max(params_.ekf.initial_landmark_capacity, 1));
  point_kind_ = ekf_.RegisterKind(kCooperativePointKind);
  for (int v = 0; v < vehicles_; ++v) {
    if (Tracks(v)) ekf_.AddBlock(kPoseKind, start_poses[v].vector(), pose_cov);
    fej_models_[v].Clear();
    fej_models_[v].SetPriorPose(start_poses[v]);
  }
  landmarks_.Clear();
  latest_.assign(vehicles_, {});
  counts_ = {};
  updates_ = 0;
  health_checks_ = 0;
}

int CooperativeEkfSlam::BlockOfVehicle(int vehicle) const {
  if (vehicle < 0 || vehicle >= vehicles_ || block_of_[vehicle] < 0) {
    throw std::invalid_argument("CooperativeEkfSlam: vehicle " + std::to_string(vehicle) +
                                " is not tracked by this filter");
  }
  return block_of_[vehicle];
}

// SPEC S2, Eq. 2; for another vehicle, with the controls it shares (SPEC S3).
void CooperativeEkfSlam::Predict(int vehicle, const Control& u, double dt_s,
                                 const ControlCovariance* control_noise) {
  if (vehicle < 0 || vehicle >= vehicles_ || !Tracks(vehicle)) return;
  if (!u.allFinite() || !std::isfinite(dt_s) || (control_noise && !control_noise->allFinite())) {
    throw std::invalid_argument("CooperativeEkfSlam::Predict: non-finite control or time step");
  }
  const int block = block_of_[vehicle];
  Eigen::Matrix3d J_x_x;
  ControlJacobian J_x_u;
  const Pose2 moved = motion_->Move(ekf_.PoseOf(block), u, dt_s, &J_x_x, &J_x_u);
  if (params_.ekf.jacobians == JacobianEstimates::kFirstEstimates) {
    FirstEstimatesMotionJacobian(moved, fej_models_[vehicle].prior_pose(), &J_x_x);
  }
  fej_models_[vehicle].SetPriorPose(moved);
  ekf_.PredictPose(block, moved, J_x_x, J_x_u,
                   control_noise ? *control_noise : motion_->Noise(u, dt_s));
}

// SPEC S3: a v-v sighting relates two pose blocks; its identity is known (no association).
// Linearised at the current estimates whatever params.ekf.jacobians says: first estimates cover
// the motion and the landmark sightings only.
void CooperativeEkfSlam::ApplyVehicleSighting(int observer, const VehicleObservation& obs) {
  const int a = block_of_[observer], b = block_of_[obs.target];
  if (a < 0 || b < 0) return;
  Eigen::Matrix<double, 2, 3> J_a, J_b;
  const RangeBearing z_pred = PredictVehicleSighting(ekf_.PoseOf(a), ekf_.PoseOf(b), &J_a, &J_b);
  Linearisation lin;
  lin.innovation = Eigen::Vector2d(obs.z.x() - z_pred.range_m,
                                   WrapAngle(obs.z.y() - z_pred.bearing_rad));
  lin.H.Add(a, J_a);
  lin.H.Add(b, J_b);
  lin.R = obs.R;
  if (ekf_.MahalanobisSquared(lin) > params_.vehicle_gate_chi2) {
    ++counts_.vehicle_gated;
    return;
  }
  if (ekf_.Update(lin)) ++counts_.vehicle_updates;
}

// SPEC S3, seed 002 Eqs. 8-14: `scan` of another vehicle b, each landmark sighting composed with
// self's latest v-v sighting of b into a sighting from self, with R^e. Empty without one.
std::vector<PointObservation> CooperativeEkfSlam::Extended(const FleetScan& scan) const {
  const LatestSighting& vv = latest_[scan.vehicle];
  const double age = scan.t_s - vv.t_s;
  if (age < -1e-9 || age > params_.extended_max_age_s + 1e-9) return {};
  const int a = block_of_[self_], b = block_of_[scan.vehicle];
  const double relative_heading = WrapAngle(ekf_.PoseOf(b).theta() - ekf_.PoseOf(a).theta());
  double heading_variance = 0.0;
  if (params_.extended_heading_noise) {
    const Eigen::MatrixXd P_ab = ekf_.CovarianceBlock(a, b);
    heading_variance = ekf_.CovarianceBlock(a, a)(2, 2) + ekf_.CovarianceBlock(b, b)(2, 2) -
                       2.0 * P_ab(2, 2);
  }
  std::vector<PointObservation> extended;
  for (const PointObservation& s : scan.landmarks) {
    ExtendedObservationJacobian J;
    const RangeBearing z = ComposeExtendedObservation(
        {vv.obs.z.x(), vv.obs.z.y()}, {s.z.x(), s.z.y()}, relative_heading, &J);
    PointObservation e;
    e.z = {z.range_m, z.bearing_rad};
    e.R = ExtendedObservationCovariance(J, vv.obs.R, s.R, std::max(heading_variance, 0.0));
    e.id = s.id;
    extended.push_back(e);
  }
  return extended;
}

// With kFirstEstimates, H from the vehicle's FirstEstimatesPointModel (Huang, Mourikis,
// Roumeliotis 2008, Sec. IV); the innovation always from the current means.
const ObservationModel& CooperativeEkfSlam::UpdateModel(int vehicle) const {
  if (params_.ekf.jacobians == JacobianEstimates::kFirstEstimates) return fej_models_[vehicle];
  return point_model_;
}

// The UpdatePipeline from pose block `block`, on the whole scan for a per-scan associator or
// schedule, else one sighting at a time (EkfSlam's schedules).
std::vector<AssociationDecision> CooperativeEkfSlam::RunPipeline(
    int vehicle, std::span<const PointObservation> sightings) {
  const EkfSlamParams& p = params_.ekf;
  const int block = block_of_[vehicle];
  const int before = NumLandmarks();
  const bool per_scan = p.schedule == UpdateSchedule::kPerScan ||
                        p.association_method == AssociationMethod::kJointCompatibility ||
                        p.association_method == AssociationMethod::kGlobalNearestNeighbour;
  std::vector<char> taken(landmarks_.size() + sightings.size(), 0);
  std::vector<AssociationDecision> decisions;
  const std::size_t part = per_scan ? std::max<std::size_t>(sightings.size(), 1) : 1;
  for (std::size_t i = 0; i < sightings.size(); i += part) {
    PointSightings points({&point_model_, &UpdateModel(vehicle), associator_.get()}, landmarks_,
                          sightings.subspan(i, std::min(part, sightings.size() - i)), taken);
    LandmarkSightings* const kinds[] = {&points};
    UpdatePipeline pipeline(ekf_, block, kinds);
    pipeline.Run(*selection_, false);
    MarkTaken(pipeline.Decisions(0), taken);
    decisions.insert(decisions.end(), pipeline.Decisions(0).begin(), pipeline.Decisions(0).end());
  }
  // Huang et al. 2008, Sec. IV: each new landmark's first estimate, its initialised mean.
  for (int l = before; l < NumLandmarks(); ++l) {
    for (FirstEstimatesPointModel& m : fej_models_) {
      m.Record(landmarks_.Block(l), ekf_.Mean(landmarks_.Block(l)));
    }
  }
  for (const AssociationDecision& d : decisions) {
    counts_.landmark_updates += d.kind == AssociationDecision::Kind::kMatched;
    counts_.landmark_dropped += d.kind == AssociationDecision::Kind::kDropped;
  }
  return decisions;
}

std::vector<AssociationDecision> CooperativeEkfSlam::Update(const FleetScan& scan) {
  CheckScan(scan, vehicles_);
  std::vector<AssociationDecision> decisions(scan.landmarks.size());
  const bool own = scan.vehicle == self_;
  switch (params_.mode) {
    case CooperativeMode::kMono:
      if (own) decisions = RunPipeline(self_, scan.landmarks);
      break;
    case CooperativeMode::kExtended:
      if (own) {
        for (const VehicleObservation& obs : scan.vehicles) {
          ApplyVehicleSighting(self_, obs);
          latest_[obs.target] = {scan.t_s, obs};
        }
        decisions = RunPipeline(self_, scan.landmarks);
      } else {
        const std::vector<PointObservation> extended = Extended(scan);
        counts_.extended += static_cast<long>(extended.size());
        if (!extended.empty()) decisions = RunPipeline(self_, extended);
      }
      break;
    case CooperativeMode::kExact:
      for (const VehicleObservation& obs : scan.vehicles) ApplyVehicleSighting(scan.vehicle, obs);
      decisions = RunPipeline(scan.vehicle, scan.landmarks);
      break;
  }
  ekf_.ApplyPendingDowndate();
  ++updates_;
  CheckHealthAfterUpdate();
  return decisions;
}

void CooperativeEkfSlam::CheckHealthAfterUpdate() {
  if (!params_.ekf.health.every_update()) return;
  ++health_checks_;
  const bool psd = params_.ekf.health.PsdDue(health_checks_, StateSize());
  if (auto problem = ekf_.HealthProblem(params_.ekf.health, psd)) {
    ThrowNumericalError("CooperativeEkfSlam after update " + std::to_string(updates_) + " (" +
                            std::to_string(NumLandmarks()) + " landmarks)",
                        *problem);
  }
}

void CooperativeEkfSlam::CheckOutputHealth() const {
  if (params_.ekf.health.enabled()) {
    ekf_.CheckHealth(params_.ekf.health, true, "CooperativeEkfSlam at output");
  }
}

Eigen::Matrix3d CooperativeEkfSlam::PoseCovarianceOf(int vehicle) const {
  const int block = BlockOfVehicle(vehicle);
  return ekf_.CovarianceBlock(block, block);
}

LandmarkMap CooperativeEkfSlam::Map() const {
  LandmarkMap map;
  for (int i = 0; i < NumLandmarks(); ++i) {
    const int block = landmarks_.Block(i);
    map.landmarks.push_back(
        {landmarks_.SourceId(i), ekf_.Mean(block), ekf_.CovarianceBlock(block, block)});
  }
  return map;
}

}  // namespace slamkit
