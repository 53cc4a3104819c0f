#pragma once

// The per-particle steps of FastSlam (private to src/filters): what one particle does with a
// control and with a scan, reading only what the filter shares read-only during the parallel loop.

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/data_association.hpp"
#include "slamkit/filters/fastslam.hpp"
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
