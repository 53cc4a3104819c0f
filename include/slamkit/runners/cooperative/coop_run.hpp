#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/fleet_log.hpp"
#include "slamkit/filters/cooperative/cooperative_ekf_slam.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/unicycle.hpp"
#include "slamkit/sim/fleet.hpp"

namespace slamkit {

// The estimators a cooperative run compares (SPEC S3; docs/cooperative.md).
enum class CoopMode {
  kDeadReckoning,  // each vehicle's controls integrated, no sighting used
  kMono,           // CooperativeMode::kMono per vehicle
  kExtended,       // CooperativeMode::kExtended per vehicle (the seed's EO-CSLAM)
  kExact,          // CooperativeMode::kExact per vehicle, each fed what reaches it
  kCentral,        // one CooperativeMode::kExact filter fed every event
  // Not a filter: the batch maximum a posteriori of each vehicle's own data, what Mono uses
  // (eval's SmoothLandmarkSlam from the Mono filter's path, the sightings' true ids). It uses
  // later data too, so it shows what a Mono filter could reach at best on a log; no covariance.
  kMonoSmoothed,
};
// "dead-reckoning", "mono", "eo", "eo-exact", "central", "mono-smoothed"
std::string_view CoopModeName(CoopMode mode);
std::optional<CoopMode> CoopModeFromName(std::string_view name);
// Whether a mode's estimates carry a covariance (NEES, ‖C‖, IR): every filter's.
bool HasCovariance(CoopMode mode);

// What the filters of a cooperative run are made of, and what they are told.
struct CoopFilterParams {
  CooperativeEkfSlamParams filter;  // its mode is set per run
  UnicycleParams motion;            // the filters' control noise, per control interval
  // When set, the control noise as a density (σ_v² [m²/s], σ_ω² [rad²/s]): an interval of dt
  // gets Q = density / dt, so that the noise a vehicle accumulates does not depend on how its
  // controls are split (real logs, whose control intervals vary).
  std::optional<Eigen::Vector2d> control_noise_density;
  RangeBearingParams sensor;          // landmark sightings' noise, and the reach of association
  RangeBearingParams vehicle_sensor;  // v-v sightings' noise
  MessageParams messages;
  // Sightings keep the source's landmark ids (a simulator's truth, a data set's barcodes).
  bool known_association = true;
  // With known ids, a sighting farther than this chi-square from its landmark is dropped as an
  // outlier (KnownAssociation's gate; infinity: none).
  double known_gate_chi2 = std::numeric_limits<double>::infinity();
  // Estimates are recorded at each control of the vehicle, at most this often [s] (0: each).
  double record_period_s = 0.0;
};

// One vehicle as its estimator saw it, at the times of the record: its controls' times (at most
// one per record_period_s) where the truth has a sample within 0.5 s.
struct CoopVehicleTrace {
  Trajectory estimate;
  std::vector<Eigen::Matrix3d> covariance;  // zero for dead reckoning
  Trajectory truth;                          // the true pose at each recorded time
  // Figures over the record: position and heading RMSE, the pose NEES (3 dof; NaN where the
  // covariance is singular: the known start, dead reckoning) and its mean where defined, and
  // the spectral norm of the position covariance (the seed's ‖C‖).
  double position_rmse_m = 0.0;
  double heading_rmse_rad = 0.0;
  // The position RMSE once the whole recorded path is rigidly aligned to the truth (eval's
  // AlignPoints): the error that a shift and a turn of the frame do not explain; -1 below two
  // records.
  double position_aligned_rmse_m = -1.0;
  double mean_nees = 0.0;
  std::vector<double> nees;
  std::vector<double> position_cov_norm;
  // The vehicle's map (the central filter's for kCentral) against the truth after a rigid
  // alignment, over the landmarks whose true id is known (-1: no landmark to compare).
  LandmarkMap map;
  double map_rmse_m = -1.0;
  // The share of the filter's landmark sightings (matched or new) that fall on a one-to-one
  // pairing of its landmarks with the true ids (eval's AssociationAgreement), over the sightings
  // whose true id is known; -1 when none is. 1 with known association unless the gate dropped a
  // landmark's first sighting.
  double association_agreement = -1.0;
  CooperativeEkfSlam::Counts counts;  // its filter's (the central filter's for kCentral)
};

struct CoopModeResult {
  CoopMode mode = CoopMode::kMono;
  std::vector<CoopVehicleTrace> vehicles;
  double update_time_mean_s = 0.0;  // per scan update (one filter's), wall clock
  long scans = 0;                   // scan updates over all the run's filters
  CooperativeEkfSlam::Counts counts;  // summed over the run's filters
};

// One estimator over `log`: each vehicle's filter (or the central one) takes its own events and
// what reaches it (DeliveredEvents, loss drawn from Rng(message_seed + receiver)), moving each
// tracked vehicle to a sighting's time with its latest control before the sighting is used.
// `true_ids` (parallel to log.events, or empty) names each sighting's true landmark for the map
// error and, with known_association, the filters' ids; empty keeps the log's own ids.
CoopModeResult RunCoopMode(const FleetLog& log, const FleetTruth& truth,
                           const std::vector<LandmarkId>& true_ids, CoopMode mode,
                           const CoopFilterParams& params, std::uint64_t message_seed);

// SPEC S3's improvement ratio over time, (‖C‖_mono − ‖C‖) / ‖C‖_mono in %, at each of the
// other record's times t against Mono's record at t or the latest before it (a filter that runs
// behind real time for delayed messages records later times than Mono); records before Mono's
// first are left out.
std::vector<double> ImprovementRatio(const std::vector<double>& mono_t_s,
                                     const std::vector<double>& mono_norm,
                                     const std::vector<double>& t_s,
                                     const std::vector<double>& norm);
std::vector<double> ImprovementRatio(const CoopVehicleTrace& mono, const CoopVehicleTrace& other);

}  // namespace slamkit
