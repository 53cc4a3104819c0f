#pragma once

// The per-particle steps of FastSlam (private to src/filters): what one particle does with a
// control and with a scan, reading only what the filter shares read-only during the parallel loop.

#include <cstdint>
#include <limits>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit::fastslam_detail {

// The filter-wide grid of landmark slots by where they were first mapped: cell key → slots.
using SlotGrid = std::unordered_map<std::int64_t, std::vector<int>>;

std::int64_t CellKey(const Eigen::Vector2d& p_m, double cell_m);
// The slots filed in the cells that overlap the square of half-side `radius_m` around `center`,
// in cell then filing order (deterministic).
void SlotsNear(const SlotGrid& grid, const Eigen::Vector2d& center, double radius_m,
               double cell_m, std::vector<int>& out);

// What a particle's update reads; shared by all particles and not changed during the loop.
struct ScanInputs {
  const FastSlamParams& params;
  const PointSensorModel& sensor;
  std::span<const PointObservation> observations;
  const SlotGrid& grid;
  const std::unordered_map<LandmarkId, int>& slot_of_id;
};

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A landmark of the particle near its pose, loaded once per scan and written back if changed.
struct Candidate {
  int slot = -1;
  FastSlamLandmark landmark;
  bool taken = false;    // a sighting of this scan was matched to it
  bool changed = false;  // to be written back (or erased, at evidence ≤ 0)
};

// ln of the density of a 2-D Gaussian of covariance S at squared Mahalanobis distance `chi2`.
double LogGaussianDensity(double chi2, const Eigen::Matrix2d& S);
// Montemerlo et al. 2003, Sec. 4: the likelihood p0 a sighting must beat to be matched, here the
// density of N(0, R) at squared Mahalanobis distance `chi2`, so it scales with the sensor.
double LogNewLandmarkLikelihood(const Eigen::Matrix2d& R, double chi2);
// The particle's landmarks within the sensor's range (plus the association margin) of its pose.
std::vector<Candidate> GatherCandidates(const FastSlamParticle& p, const ScanInputs& scan);
// Montemerlo et al. 2002, Eqs. 4-6: the landmark's EKF update with the sighting from pose `x`.
void UpdateLandmark(Candidate& c, const Pose2& x, const PointObservation& obs,
                    const PointSensorModel& sensor);
// Stores the changed candidates in the particle's tree (erasing those at evidence ≤ 0).
void WriteBack(FastSlamParticle& p, const std::vector<Candidate>& candidates);

// delayed_sampling: the covariance of [pose; window landmarks] carried through one motion step.
void PropagateWindow(Eigen::MatrixXd& P, const Eigen::Matrix3d& J_x, const Eigen::Matrix3d& noise);
// delayed_sampling: UpdateParticle for a particle that holds a window (fastslam_window.cpp).
void UpdateWithWindow(FastSlamParticle& p, const ScanInputs& scan, Rng& rng, ParticleUpdate& out);

// The particle's prediction: a motion sample (FastSLAM 1.0) or its predicted pose Gaussian (2.0).
void PredictParticle(FastSlamParticle& p, const MotionModel& motion, FastSlamProposal proposal,
                     const Control& u, double dt_s, const ControlCovariance& Q, Rng& rng);

// Association, pose sample (2.0), landmark updates, negative evidence and the weight factor of
// one scan, into `out` (its buffers reused). Landmarks created here are left to the caller
// (InsertCreated) once slots exist.
void UpdateParticle(FastSlamParticle& p, const ScanInputs& scan, Rng& rng, ParticleUpdate& out);

// Stores the particle's new landmarks under the slots the filter gave their sightings.
void InsertCreated(FastSlamParticle& p, const ParticleUpdate& update,
                   const std::vector<int>& slot_of_observation);

}  // namespace slamkit::fastslam_detail
