#pragma once

#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/ekf_slam/point_landmarks.hpp"
#include "slamkit/filters/selection/selection.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// What one vehicle's filter does with the fleet's measurements (SPEC S3; docs/cooperative.md).
enum class CooperativeMode {
  // Mono-SLAM: the vehicle alone, its own controls and landmark sightings.
  kMono,
  // EO-CSLAM as seed 002 formulates it: the other vehicles' poses are tracked with their shared
  // controls and corrected by the vehicle's own v-v sightings of them; another vehicle's landmark
  // sightings become extended observations (ComposeExtendedObservation) through the vehicle's
  // latest v-v sighting of it, each updated as an independent measurement. One v-v sighting
  // then counts once directly and once per sighting it extends.
  kExtended,
  // Every raw measurement once, on the blocks it relates: a landmark sighting from its
  // observer's pose block, a v-v sighting between two pose blocks. Given every message, this is
  // the centralised filter over the whole fleet.
  kExact,
};

// A v-v sighting in a scan: vehicle `target` at range and bearing `z` with noise `R`.
struct VehicleObservation {
  int target = -1;
  Eigen::Vector2d z = Eigen::Vector2d::Zero();
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
};

// What one vehicle sensed at one time: its landmark sightings and its v-v sightings.
struct FleetScan {
  int vehicle = 0;
  double t_s = 0.0;
  std::vector<PointObservation> landmarks;
  std::vector<VehicleObservation> vehicles;
};

struct CooperativeEkfSlamParams {
  CooperativeMode mode = CooperativeMode::kExact;
  // Association, reach margin, state capacity and health checks, as for EkfSlam (its
  // `jacobians` and `selection_diagnostics` are not used).
  EkfSlamParams ekf;
  // kExtended: the oldest v-v sighting of another vehicle that may extend its scan [s] (0: only
  // one taken at the scan's time, as in a synchronous simulation).
  double extended_max_age_s = 0.0;
  // kExtended: whether R^e includes the variance of the two vehicles' relative heading, which
  // the composition also depends on (on: the composition's full first-order noise).
  bool extended_heading_noise = true;
  // A v-v sighting whose squared Mahalanobis distance exceeds this is not applied (an outlier
  // gate; infinity: none).
  double vehicle_gate_chi2 = std::numeric_limits<double>::infinity();
};

// Cooperative EKF-SLAM for a fleet of `vehicles` (SPEC S3): one BlockEkf with a pose block per
// tracked vehicle (only `self` in kMono; all of them otherwise) and the point landmarks, updated
// scan by scan through the UpdatePipeline (association, selection, sequential updates,
// augmentation) from whichever pose block the mode says. `self` is the vehicle whose filter
// this is; -1 makes the centralised filter (every vehicle its own, kExact only).
class CooperativeEkfSlam {
 public:
  CooperativeEkfSlam(const CooperativeEkfSlamParams& params, int vehicles, int self,
                     std::unique_ptr<MotionModel> motion, std::unique_ptr<PointSensorModel> sensor,
                     std::unique_ptr<Associator> associator = {},
                     std::unique_ptr<SelectionPolicy> selection = {});

  // Forgets the map; the tracked vehicles start at their `start_poses` (one per vehicle).
  void Reset(std::span<const Pose2> start_poses,
             const Eigen::Matrix3d& pose_cov = Eigen::Matrix3d::Zero());
  bool Tracks(int vehicle) const { return block_of_[vehicle] >= 0; }
  // SPEC S2, Eq. 2 on vehicle `vehicle`'s pose block (nothing if it is not tracked);
  // `control_noise` overrides the motion model's.
  void Predict(int vehicle, const Control& u, double dt_s,
               const ControlCovariance* control_noise = nullptr);
  // One scan of the fleet, used as the mode says; one decision per landmark sighting, in order
  // (kDropped for those the mode does not use). Throws std::invalid_argument on a non-finite
  // value or a vehicle out of range.
  std::vector<AssociationDecision> Update(const FleetScan& scan);
  // The full health check unless params.ekf.health.mode is kOff; NumericalError if it fails.
  void CheckOutputHealth() const;

  Pose2 PoseOf(int vehicle) const { return ekf_.PoseOf(BlockOfVehicle(vehicle)); }
  Eigen::Matrix3d PoseCovarianceOf(int vehicle) const;
  int NumLandmarks() const { return landmarks_.size(); }
  LandmarkMap Map() const;
  int StateSize() const { return ekf_.StateSize(); }
  // Since Reset(): the v-v sightings applied and gated out, the extended observations made, and
  // the landmark sightings (local or extended) that updated a landmark or were dropped by the gate.
  struct Counts {
    long vehicle_updates = 0;
    long vehicle_gated = 0;
    long extended = 0;
    long landmark_updates = 0;
    long landmark_dropped = 0;
  };
  const Counts& counts() const { return counts_; }
  const CooperativeEkfSlamParams& params() const { return params_; }
  const BlockEkf& ekf() const { return ekf_; }

 private:
  struct LatestSighting {
    double t_s = -1e300;
    VehicleObservation obs;
  };
  int BlockOfVehicle(int vehicle) const;
  void ApplyVehicleSighting(int observer, const VehicleObservation& obs);
  std::vector<PointObservation> Extended(const FleetScan& scan) const;
  std::vector<AssociationDecision> RunPipeline(int vehicle,
                                               std::span<const PointObservation> sightings);
  void CheckHealthAfterUpdate();
  const ObservationModel& UpdateModel(int vehicle) const;

  CooperativeEkfSlamParams params_;
  int vehicles_;
  int self_;
  std::unique_ptr<MotionModel> motion_;
  std::unique_ptr<PointSensorModel> sensor_;
  std::unique_ptr<Associator> associator_;
  std::unique_ptr<SelectionPolicy> selection_;
  BlockEkf ekf_;
  int point_kind_ = -1;
  PointLandmarkModel point_model_;
  // Per vehicle: the updates' model with params.ekf.jacobians == kFirstEstimates (its prior pose
  // is that vehicle's latest prediction; every one records each landmark's first estimate).
  std::vector<FirstEstimatesPointModel> fej_models_;
  PointLandmarkMap landmarks_;
  std::vector<int> block_of_;  // per vehicle: its pose block, -1 when not tracked
  std::vector<LatestSighting> latest_;  // kExtended: self's latest v-v sighting of each vehicle
  Counts counts_;
  long updates_ = 0;
  long health_checks_ = 0;
};

}  // namespace slamkit
