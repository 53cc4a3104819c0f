#pragma once

#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/data_association.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

struct EkfSlamParams {
  // Use each observation's id as its landmark (simulator truth or a data set's association)
  // instead of nearest-neighbour association.
  bool known_association = false;
  AssociationParams association;
  // A landmark farther than the sensor's range plus this margin from the estimated pose is not
  // considered for association (saves the Mahalanobis test on landmarks that cannot be seen).
  double association_margin_m = 5.0;
  // Landmark slots allocated up front; the state grows by doubling beyond this.
  int initial_landmark_capacity = 64;
};

// EKF-SLAM on an augmented state x = [x_v, m_1 … m_N] with point landmarks (SPEC S1 item 1, S2).
//
// Only the upper triangle of the covariance is stored and updated: prediction touches the pose
// rows (O(n)), each observation's sequential update is a symmetric rank-2 downdate of that
// triangle (O(n²)), and augmentation appends two columns (O(n)).
//
// Within one Update() the rank-2 downdates of its observations are deferred: the covariance is
// kept as P₀ − U Uᵀ, each observation reads the few columns it needs through that correction
// (O(n·m)) and appends its two columns to U, and the whole step's downdate P₀ − U Uᵀ is applied
// in one pass over the triangle at the end. The result is the sequential EKF's (each observation
// is linearised at the mean its predecessors left) with one pass over memory instead of m.
class EkfSlam {
 public:
  EkfSlam(const EkfSlamParams& params, std::unique_ptr<MotionModel> motion,
          std::unique_ptr<PointSensorModel> sensor);

  // Forgets the map and starts from `pose` with covariance `pose_cov`.
  void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov = Eigen::Matrix3d::Zero());

  // SPEC S2, Eq. 2 and Table 10.1 of Probabilistic Robotics: moves the pose with control `u`.
  // `control_noise` overrides the motion model's noise (a data set's own odometry covariance).
  void Predict(const Control& u, double dt_s, const ControlCovariance* control_noise = nullptr);

  // Associates, updates with and augments by each observation in turn (sequential EKF).
  // Throws std::invalid_argument on a non-finite measurement or covariance.
  std::vector<AssociationDecision> Update(std::span<const PointObservation> observations);

  // One sequential update of landmark `landmark` with `obs` (Table 10.2, one innovation).
  void UpdateLandmark(int landmark, const PointObservation& obs) {
    UpdateLandmarkDeferred(landmark, obs);
    ApplyDeferredDowndate();
  }
  // Adds a landmark initialised from `obs` by the inverse sensor model (SPEC S2, Eq. 8).
  int AddLandmark(const PointObservation& obs);
  // Squared Mahalanobis distance of `obs` from landmark `landmark`'s predicted measurement.
  double MahalanobisDistance(int landmark, const PointObservation& obs) const;

  Pose2 pose() const { return Pose2(x_.head<3>()); }
  Eigen::Matrix3d PoseCovariance() const;
  int NumLandmarks() const { return static_cast<int>(source_ids_.size()); }
  int StateSize() const { return n_; }
  Eigen::Vector2d LandmarkPosition(int landmark) const { return x_.segment<2>(Offset(landmark)); }
  Eigen::Matrix2d LandmarkCovariance(int landmark) const;
  // The id of the observation that created the landmark (kNoLandmark if it had none).
  LandmarkId LandmarkSourceId(int landmark) const { return source_ids_[landmark]; }
  // The estimated landmarks with their marginal covariances.
  LandmarkMap Map() const;
  // The full symmetric covariance (a copy; O(n²), for tests and output).
  Eigen::MatrixXd Covariance() const;
  Eigen::VectorXd State() const { return x_.head(n_); }
  const EkfSlamParams& params() const { return params_; }

 private:
  static int Offset(int landmark) { return 3 + 2 * landmark; }
  // Columns [c, c+k) of the current covariance P₀ − U Uᵀ, gathered from the stored triangle.
  Eigen::MatrixXd CurrentColumns(int c, int k) const;
  // Columns 0-2 (the pose's) of the current covariance; cached while downdates are deferred.
  Eigen::MatrixXd CurrentPoseColumns() const;
  // A small block of the current covariance: rows [r, r+R), columns [c, c+C).
  template <int R, int C>
  Eigen::Matrix<double, R, C> CurrentBlock(int r, int c) const;
  void UpdateLandmarkDeferred(int landmark, const PointObservation& obs);
  // P₀ ← P₀ − U Uᵀ on the upper triangle, in fixed column blocks run in parallel.
  void ApplyDeferredDowndate();
  Eigen::Matrix2d InnovationCovariance(int landmark, const Eigen::Matrix<double, 2, 3>& H_x,
                                       const Eigen::Matrix2d& H_l, const Eigen::Matrix2d& R) const;
  AssociationDecision AssociateNearest(const PointObservation& obs,
                                       const std::vector<char>& used) const;
  AssociationDecision AssociateKnown(const PointObservation& obs) const;
  void Reserve(int state_size);

  EkfSlamParams params_;
  std::unique_ptr<MotionModel> motion_;
  std::unique_ptr<PointSensorModel> sensor_;
  NearestNeighbourAssociator associator_;
  int n_ = 3;
  Eigen::VectorXd x_;  // capacity-sized; the first n_ entries are the state
  Eigen::MatrixXd P_;  // capacity-sized; upper triangle of the leading n_×n_ block is valid
  Eigen::MatrixXd U_;  // capacity rows; the first m_ columns are the deferred downdate factor
  Eigen::MatrixXd pose_cols_;  // capacity×3: the current pose columns while m_ > 0
  int m_ = 0;
  std::vector<LandmarkId> source_ids_;
  std::unordered_map<LandmarkId, int> index_of_id_;
  mutable std::vector<AssociationCandidate> candidates_;  // scratch, reused across calls
};

}  // namespace slamkit
