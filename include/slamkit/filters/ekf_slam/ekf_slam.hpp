#pragma once

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/state_health.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/association/jcbb.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/first_estimates.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/ekf_slam/active_area.hpp"
#include "slamkit/filters/ekf_slam/point_landmarks.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/filters/selection/selection.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// The associators EkfSlamParams can name (configuration files, the CLI); any other Associator
// can be passed to the EkfSlam constructor.
enum class AssociationMethod {
  kNearestNeighbour,  // SPEC S2, Eqs. 6-7
  kKnown,             // each observation's id is its landmark (simulator truth, a data set's)
  kJointCompatibility,  // JCBB (Neira & Tardós 2001), over the whole scan (see `schedule`)
  kMaximumLikelihood,   // the most likely landmark within the gate (MaximumLikelihoodAssociator)
  kGlobalNearestNeighbour,  // the scan's gated pairs, nearest first (per scan, as JCBB)
};

// When association runs relative to the updates of a scan.
enum class UpdateSchedule {
  // Each observation in turn is associated against the posterior its predecessors left, then
  // applied (Probabilistic Robotics Table 10.3). The steps below run on one observation at a time.
  kPerObservation,
  // The whole scan is associated against the prior, then selected, updated and augmented: what
  // joint association (JCBB) and a selection policy ranking the scan (SPEC S1 item 3) need.
  kPerScan,
};

struct EkfSlamParams {
  AssociationMethod association_method = AssociationMethod::kNearestNeighbour;
  AssociationParams association;
  JcbbParams jcbb;  // with kJointCompatibility
  // kJointCompatibility and kGlobalNearestNeighbour need the whole scan at once: with them the
  // schedule is always kPerScan.
  UpdateSchedule schedule = UpdateSchedule::kPerObservation;
  // A landmark farther than the sensor's range plus this margin from the estimated pose is not
  // considered for association (saves the Mahalanobis test on landmarks that cannot be seen).
  double association_margin_m = 5.0;
  // Landmark slots allocated up front; the state grows by doubling beyond this.
  int initial_landmark_capacity = 64;
  // When the state's health is checked (finite, symmetric, PSD; see StateHealthParams for the
  // schedule): every update in Debug and sanitizer builds, at output in Release.
  StateHealthParams health;
  // Whether each step also runs the full sequential update of every matched observation on the
  // marginal of the blocks they touch (BlockEkf::Marginal, O(k²) in their k entries; per
  // observation on the per-observation schedule), so that LastSelectionStats() has the accuracy
  // ratio of SPEC S1, Eq. 24.
  bool selection_diagnostics = false;
  // Where the updates and predictions linearise: kCurrent, the textbook EKF; kFirstEstimates, the
  // FEJ-EKF (Huang, Mourikis, Roumeliotis 2008), whose motion Jacobian uses the predicted poses
  // and whose measurement Jacobians use the scan's predicted pose and each landmark's first
  // estimate. Association (the Mahalanobis gate, JCBB's joint test) and augmentation always use
  // the current estimates. FEJ assumes a motion p' = p + R(θ)·δ(u), θ' = θ + Δθ(u) (car-like,
  // unicycle, odometry models).
  JacobianEstimates jacobians = JacobianEstimates::kCurrent;
  // kCompressed: each scan's updates touch the active area only (Guivant & Nebot 2001), and the
  // rest of the state is brought up to date when the vehicle leaves the area or the whole state
  // is read (Covariance(), State(), Map(), CheckOutputHealth()). The estimate is the dense
  // filter's up to rounding; association considers the area's landmarks, which hold every
  // landmark within reach.
  EkfUpdateMode update = EkfUpdateMode::kDense;
  ActiveAreaParams active_area;  // with kCompressed

  bool known_association() const { return association_method == AssociationMethod::kKnown; }
};

// The associator `params` names.
std::unique_ptr<Associator> MakeAssociator(const EkfSlamParams& params);

// EKF-SLAM with point landmarks (SPEC S1 item 1, S2): a BlockEkf holding one pose and point
// landmarks, and an update that is the UpdatePipeline of injected steps over the point kind
// (PointSightings): association (an Associator), selection (a SelectionPolicy), the sequential
// updates, augmentation of the new landmarks. The updates of one Update() share one deferred
// covariance downdate (see BlockEkf).
class EkfSlam final : public LandmarkSlamFilter {
 public:
  // `associator` defaults to the one params names, `selection` to SelectAll. A policy that ranks
  // the scan (SPEC S1 items 2 and 3) needs UpdateSchedule::kPerScan: per observation, it is
  // offered one observation at a time.
  EkfSlam(const EkfSlamParams& params, std::unique_ptr<MotionModel> motion,
          std::unique_ptr<PointSensorModel> sensor, std::unique_ptr<Associator> associator = {},
          std::unique_ptr<SelectionPolicy> selection = {});

  void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov = Eigen::Matrix3d::Zero()) override;
  // SPEC S2, Eq. 2 and Table 10.1 of Probabilistic Robotics: moves the pose with control `u`.
  // Throws std::invalid_argument on a non-finite control, time step or noise (before any change);
  // with health.every_update(), NumericalError if the moved pose or its covariance rows are not
  // finite.
  void Predict(const Control& u, double dt_s,
               const ControlCovariance* control_noise = nullptr) override;
  // Association, selection, sequential updates and augmentation of one scan.
  // Throws std::invalid_argument on a non-finite measurement or covariance (before any change);
  // with health.every_update(), NumericalError if the resulting state is not healthy (unless
  // nothing changed it: an empty scan after a prediction, which checks what it changes).
  std::vector<AssociationDecision> Update(std::span<const PointObservation> observations) override;
  // The full check (finite, symmetric, PSD) unless health.mode is kOff; NumericalError if it fails.
  void CheckOutputHealth() const override;
  void Flush() override { Synchronise(); }
  // With compressed updates: global_updates, global_update_s and max_active_size.
  std::vector<FilterCounter> Counters() const override;

  // One sequential update of landmark `landmark` with `obs` (Table 10.2, one innovation). The
  // covariance downdate stays deferred until ApplyPendingDowndate(), Predict() or Update();
  // reads in between see the updated covariance.
  void UpdateLandmark(int landmark, const PointObservation& obs);
  // The innovation, Jacobians and noise UpdateLandmark() would apply (see params().jacobians).
  Linearisation UpdateLinearisation(int landmark, const PointObservation& obs) const;
  void ApplyPendingDowndate() { ekf_.ApplyPendingDowndate(); }
  // Adds a landmark initialised from `obs` by the inverse sensor model (SPEC S2, Eq. 8).
  int AddLandmark(const PointObservation& obs);
  // Squared Mahalanobis distance of `obs` from landmark `landmark`'s predicted measurement.
  double MahalanobisDistance(int landmark, const PointObservation& obs) const;

  Pose2 PoseEstimate() const override { return pose(); }
  Pose2 pose() const { return ekf_.PoseOf(kPoseBlock); }
  Eigen::Matrix3d PoseCovariance() const override;
  int NumLandmarks() const override { return landmarks_.size(); }
  int StateSize() const { return ekf_.StateSize(); }
  Eigen::Vector2d LandmarkPosition(int landmark) const { return ekf_.Mean(BlockOf(landmark)); }
  Eigen::Matrix2d LandmarkCovariance(int landmark) const {
    return LandmarkCovariance(landmark, landmark);
  }
  // The cross-covariance of landmarks `a` and `b` (their joint covariance's off-diagonal block).
  Eigen::Matrix2d LandmarkCovariance(int a, int b) const;
  // The id of the observation that created the landmark (kNoLandmark if it had none).
  LandmarkId LandmarkSourceId(int landmark) const { return landmarks_.SourceId(landmark); }
  LandmarkMap Map() const override;
  // The full symmetric covariance (a copy; O(n²), for tests and output; O(n²·a) while a
  // compressed area is open).
  Eigen::MatrixXd Covariance() const { return ekf_.Covariance(); }
  Eigen::VectorXd State() const { return ekf_.State(); }
  // The global update of compressed updates (nothing with dense ones): every block current.
  void Synchronise() { area_.Synchronise(ekf_); }
  // What compressed updates cost so far (zeros with dense ones).
  const CompressionStats& Compression() const { return area_.stats(); }
  const EkfSlamParams& params() const { return params_; }
  const BlockEkf& ekf() const { return ekf_; }
  // What the selection policy did in the last Update() (all parts of the scan together).
  const SelectionStats& LastSelectionStats() const { return selection_stats_; }

 private:
  static constexpr int kPoseBlock = 0;
  int BlockOf(int landmark) const { return landmarks_.Block(landmark); }
  // The observation model of the updates: point_model_, or fej_model_ with kFirstEstimates.
  const ObservationModel& UpdateModel() const;
  // Where a failed health check happened: "EkfSlam after update 5 (prediction 4, 12
  // landmarks)", "EkfSlam after prediction 4 (…)" or "EkfSlam at output (…)".
  enum class HealthStep { kUpdate, kPrediction, kOutput };
  std::string HealthWhere(HealthStep step) const;
  // The UpdatePipeline on `part` of a scan (all of it, or one observation).
  void RunPipeline(std::span<const PointObservation> part, std::vector<char>& taken,
                   std::vector<AssociationDecision>& decisions);

  EkfSlamParams params_;
  std::unique_ptr<MotionModel> motion_;
  std::unique_ptr<PointSensorModel> sensor_;
  std::unique_ptr<Associator> associator_;
  std::unique_ptr<SelectionPolicy> selection_;
  SelectionStats selection_stats_;
  BlockEkf ekf_;
  int point_kind_ = -1;
  PointLandmarkModel point_model_;
  FirstEstimatesPointModel fej_model_;  // its prior pose is kept with kCurrent too
  PointLandmarkMap landmarks_;
  ActiveArea area_;
  long predictions_ = 0;  // since Reset(), to name the step a health check failed at
  long updates_ = 0;
  long health_checks_ = 0;  // every-update checks of the whole state, for the PSD schedule
  bool unchecked_ = true;   // changed since the last every-update check other than by Predict()
};

}  // namespace slamkit
