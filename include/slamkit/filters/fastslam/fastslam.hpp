#pragma once

#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/fastslam/landmark_tree.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/filters/particles/particle_set.hpp"
#include "slamkit/filters/particles/particle_streams.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// Where a particle's new pose is drawn from.
enum class FastSlamProposal {
  // FastSLAM 1.0 (Montemerlo et al. 2002): the motion model alone.
  kMotion,
  // FastSLAM 2.0 (Montemerlo et al. 2003): the motion model conditioned on the scan's matched
  // observations, so that few particles suffice when the sensor is more precise than the motion.
  kObservation,
};

// How a particle decides that a sighting starts a new landmark.
enum class NewLandmarkTest {
  // Montemerlo et al. 2003, Sec. 4: the most likely landmark is less likely than p0.
  kLikelihood,
  // The EKF's test on the squared Mahalanobis distance under the particle's prediction (pose
  // proposal included): matched within gate_chi2, new beyond new_landmark_chi2 from every
  // landmark, dropped in between.
  kMahalanobis,
};

struct FastSlamParams {
  int particles = 100;
  FastSlamProposal proposal = FastSlamProposal::kObservation;
  // Each observation's id is its landmark (simulator truth), as EkfSlam's kKnown; otherwise each
  // particle associates by maximum likelihood.
  bool known_association = false;
  // The new-landmark likelihood p0 (Montemerlo et al. 2003, Sec. 4), as the squared Mahalanobis
  // distance at which the observation's own noise density R is taken: a sighting whose best
  // landmark is less likely than N(d² = this; R) starts a new landmark (χ²₂ at 99.9 %: 13.82).
  double new_landmark_chi2 = 13.82;
  NewLandmarkTest new_landmark_test = NewLandmarkTest::kLikelihood;
  double gate_chi2 = 9.21;  // with kMahalanobis: χ²₂ at 99 %
  // Landmarks farther than the sensor's range plus this margin from a particle's pose are not
  // considered for association or negative evidence.
  double association_margin_m = 5.0;
  // Cell size of the filter-wide grid that finds the landmarks near a pose (all particles share
  // it: a landmark is filed where it was first mapped, and stays within its first covariance).
  double index_cell_m = 10.0;
  // Montemerlo et al. 2002, Sec. 4.3: a landmark inside the sensor's view that is not seen loses
  // a count (a sighting adds one; new landmarks start at 1) and is removed at ≤ 0.
  bool negative_evidence = false;
  // The view of negative evidence: within the sensor's range less this margin, and within this
  // field of view centred on the heading (the PointSensorModel interface knows only the range).
  double negative_evidence_margin_m = 1.0;
  double negative_evidence_fov_rad = 2.0 * std::numbers::pi;
  // FastSLAM 2.0 only. A particle draws its pose only when a scan matches a landmark mapped
  // before its last draw (or its window is full); until then the pose and the landmarks mapped
  // since are one Gaussian, updated as an EKF (delayed sampling: more of the state
  // Rao-Blackwellised). Through new ground the particle then carries the path's drift in the
  // correlations, as an EKF does, where one draw per step would have to hold the true path by
  // chance. With every scan matching a known landmark it is FastSLAM 2.0.
  bool delayed_sampling = false;
  int window_max_landmarks = 40;  // a window that grows past this is drawn and emptied
  ResamplingParams resampling;  // N_eff / N below 0.5, low-variance (systematic) by default
  std::uint64_t seed = 1;
  // Particles processed in parallel (TBB) when > 1; the result is the same for any count.
  int threads = 1;
};

// One landmark EKF of one particle.
struct FastSlamLandmark {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  int evidence = 1;  // negative-evidence count
};

struct FastSlamParticle {
  Pose2 pose;
  // FastSLAM 2.0 only: the covariance of the pose predicted since the last update; the pose is
  // drawn from the proposal at the next Update(). Zero otherwise.
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  // Keyed by filter-wide landmark slot (see FastSlam), shared between copies.
  LandmarkTree<FastSlamLandmark> landmarks;
  // delayed_sampling: the landmarks mapped since the pose was last drawn (slot -1 until the
  // filter gives one), and the covariance of [pose; their positions] (size 3 + 2 × count).
  struct WindowLandmark {
    int slot = -1;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  };
  std::vector<WindowLandmark> window;
  Eigen::MatrixXd window_covariance;
};

namespace fastslam_detail {
// One particle's outcome of a scan (the filter's per-step buffer). A kNew decision's landmark is
// -1 until the filter gives the sighting a slot; `created` then holds the particle's new landmark
// (per observation, used only for kNew decisions).
struct ParticleUpdate {
  std::vector<AssociationDecision> decisions;
  std::vector<FastSlamLandmark> created;
  std::vector<int> created_in_window;  // per observation: its window index, or -1
  double log_weight = 0.0;
};
}  // namespace fastslam_detail

// FastSLAM 1.0 and 2.0 (Montemerlo et al. 2002, 2003): a particle filter over the robot's path,
// each particle with its own 2×2 landmark EKFs in a copy-on-write tree, so that resampling copies
// a particle in O(1) (plus its window's O(w²) with delayed_sampling) and a scan of k sightings
// costs O(N_particles · k · log N_landmarks).
//
// Landmark indexes. Particles associate on their own, so they may disagree on which sighting
// made a landmark. The filter names landmarks by slot: the slot of a sighting that at least one
// particle mapped as new (or, with known association, of the id), shared by every particle that
// did. Update() returns the decisions of the particle with the largest total weight after the
// scan (ParticleSet::Best()). A landmark index is given to a slot the first time such a decision
// names it, and never changes. Map() lists the best particle's landmarks under those indexes; a
// landmark the best particle does not hold (its lineage mapped that sighting elsewhere or died
// out, or negative evidence removed it) keeps the estimate it had when a decision last named it.
// The best particle's landmarks that no decision named follow, in slot order.
class FastSlam final : public LandmarkSlamFilter {
 public:
  FastSlam(const FastSlamParams& params, std::unique_ptr<MotionModel> motion,
           std::unique_ptr<PointSensorModel> sensor);

  // All particles at `pose`, or drawn from N(pose, pose_cov) when it is not zero.
  void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov = Eigen::Matrix3d::Zero()) override;
  // Samples each particle's motion (1.0), or moves its predicted pose Gaussian (2.0). Throws
  // std::invalid_argument on a non-finite control, time step or noise.
  void Predict(const Control& u, double dt_s,
               const ControlCovariance* control_noise = nullptr) override;
  // Per particle: association, pose sample (2.0), landmark EKF updates, new landmarks, weight;
  // then resampling when N_eff / N < params.resampling.threshold. Throws std::invalid_argument on
  // a non-finite measurement or covariance (before any change).
  std::vector<AssociationDecision> Update(std::span<const PointObservation> observations) override;

  // Weighted mean of the particles (heading averaged on the circle). After an Update() that
  // resampled, until the next Predict(), the mean of the weighted set before resampling: drawing
  // copies adds variance and no information (Probabilistic Robotics Sec. 4.3.4), and the copies'
  // spread, with few distinct ancestors, would understate the uncertainty.
  Pose2 PoseEstimate() const override;
  // Weighted spread of the particles about PoseEstimate(), plus their pending 2.0 covariances;
  // before resampling, as PoseEstimate().
  Eigen::Matrix3d PoseCovariance() const override;
  int NumLandmarks() const override { return static_cast<int>(Map().landmarks.size()); }
  LandmarkMap Map() const override;
  // Finite, normalisable weights; finite poses; the best particle's landmarks healthy Gaussians.
  void CheckOutputHealth() const override;

  // An initial map (a prior map; benchmarks): gives every particle the landmarks of `map`, all
  // particles sharing one tree, under indexes NumLandmarks() onwards (with known association a
  // landmark's source_id is the id that names it). Only before the first Update() after Reset();
  // std::logic_error otherwise.
  void AddLandmarks(const LandmarkMap& map);

  const ParticleSet<FastSlamParticle>& particles() const { return particles_; }
  // Normalised weights since the last resampling.
  std::vector<double> Weights() const { return particles_.Weights(); }
  bool last_update_resampled() const { return resampled_; }
  const FastSlamParams& params() const { return params_; }

 private:
  using ParticleUpdate = fastslam_detail::ParticleUpdate;
  template <class F>
  void ForEachParticle(F&& f);
  int NewSlot(const Eigen::Vector2d& position, LandmarkId source_id);
  std::vector<int> AllocateSlots(std::span<const PointObservation> observations,
                                 const std::vector<ParticleUpdate>& updates);
  std::vector<AssociationDecision> Report(const std::vector<ParticleUpdate>& updates,
                                          const std::vector<int>& slot_of_observation);
  int IndexOf(int slot);
  Pose2 WeightedMean() const;
  Eigen::Matrix3d WeightedSpread(const Pose2& mean) const;
  MappedLandmark Mapped(int slot, const FastSlamLandmark& l) const;
  // The particle's landmark of `slot`, from its tree or its window (into `scratch`), or null.
  static const FastSlamLandmark* Find(const FastSlamParticle& p, int slot,
                                      FastSlamLandmark& scratch);

  FastSlamParams params_;
  std::unique_ptr<MotionModel> motion_;
  std::unique_ptr<PointSensorModel> sensor_;
  ParticleSet<FastSlamParticle> particles_;
  ParticleStreams streams_;
  int step_ = 0;  // Predict() and Update() calls since Reset(): the particle streams' step
  bool resampled_ = false;
  bool updated_ = false;  // an Update() since Reset(): the particles' maps may differ
  // The weighted set's pose Gaussian just before the last resampling, until the next Predict().
  std::optional<std::pair<Pose2, Eigen::Matrix3d>> before_resampling_;
  // Slots: every landmark any particle holds; the grid finds them near a pose.
  std::vector<LandmarkId> slot_source_ids_;
  std::unordered_map<LandmarkId, int> slot_of_id_;
  std::unordered_map<std::int64_t, std::vector<int>> slot_grid_;
  // Landmark indexes: the slots decisions named, and what each looked like when last named.
  std::vector<int> index_of_slot_;  // -1: never named
  std::vector<int> slot_of_index_;
  std::vector<MappedLandmark> last_named_;
  // Per-particle outcomes of the scan, kept between updates so that a step allocates no large
  // block (see ParticleSet::Keep).
  std::vector<ParticleUpdate> updates_;
};

}  // namespace slamkit
