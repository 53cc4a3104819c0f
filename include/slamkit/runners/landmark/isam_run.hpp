#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/heading_drift.hpp"
#include "slamkit/eval/innovation_check.hpp"
#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/io/isam_reader.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/models/odometry_sampling.hpp"

namespace slamkit {

// How FastSLAM's particles associate and sample on a log (`slamkit run --filter
// fastslam1|fastslam2`). An unset gate is the EKF's (IsamRunParams::ekf). Without delayed
// sampling a particle's prediction holds one step's pose uncertainty, not the whole path's, so
// its innovations are wider than its covariance says wherever the particles miss the true pose:
// a log may then need wider gates than the EKF's.
struct IsamFastSlamSettings {
  NewLandmarkTest new_landmark_test = NewLandmarkTest::kLikelihood;
  std::optional<double> gate_chi2;
  std::optional<double> new_landmark_chi2;
  bool delayed_sampling = false;  // FastSlamParams::delayed_sampling (2.0 only)
  int window_max_landmarks = FastSlamParams{}.window_max_landmarks;
};

struct IsamRunParams {
  EkfSlamParams ekf;
  IsamFastSlamSettings fastslam;
  // Multiplies every odometry covariance of the file (the file's are very small).
  double odometry_covariance_scale = 1.0;
  // Multiplies every sighting covariance of the file.
  double sighting_covariance_scale = 1.0;
  // Odometry noise that grows with each step's distance and turn (OdometryNoiseSigmas), added to
  // the file's (scaled) covariance. A log may give every step the same covariance whatever the
  // vehicle did, where a wheel odometry's error grows with the motion. Zero: the file's alone.
  OdometryNoiseParams odometry_noise{0.0, 0.0, 0.0, 0.0};
  // Added to each step's turn, times the step's distance: a calibration of the vehicle's
  // odometry (a steering or wheel-radius offset turns it by a bias proportional to the distance),
  // which noise covers badly. The run reports the value its own estimate suggests
  // (IsamRunResult::odometry_heading_drift).
  double odometry_heading_drift_rad_per_m = 0.0;
  // Windows of the heading-drift fit reported with every run.
  HeadingDriftParams heading_drift_fit;
  // When both are positive, each sighting's covariance is that of a range-bearing sensor with
  // these standard deviations (mapped to the sighting's Cartesian frame), in place of the
  // file's: a laser's tree detector errs along and across the beam, not equally in x and y.
  double sighting_sigma_range_m = 0.0;
  double sighting_sigma_bearing_rad = 0.0;
  // Also score against the file's ids with its indistinguishable ids merged
  // (IndistinguishableReferenceIds): one more EKF pass, with the file's association.
  bool score_against_merged_reference = true;
  // Also compare the run with the batch least-squares solution of the log with the file's
  // associations and this run's noise (SmoothIsamLog): the file has no ground truth.
  bool compare_with_smoothed_reference = true;
};

// The log's path and landmarks by batch least squares with the file's associations
// (SmoothLandmarkSlam), started from an EKF pass with them; odometry and sightings with the
// noise, calibration and sighting model of `params`.
struct IsamSmoothedReference {
  Trajectory path;  // t = the pose's index in the file, as IsamRunResult::estimate
  std::map<LandmarkId, Eigen::Vector2d> landmarks;  // by the file's id
};

// A run against the smoothed reference. The estimate is causal (each pose before the sightings
// that follow it) and the reference is not, so ate measures mostly how far a filter strays
// before it closes its loops; map_rmse_m measures the map it ends with.
struct IsamReferenceErrors {
  AbsoluteTrajectoryErrorStats ate;  // after the best rigid alignment
  // The final map's landmarks that the association score paired one-to-one with a file id,
  // against the reference's landmarks of those ids, after the best rigid alignment.
  double map_rmse_m = 0.0;
  int landmarks_compared = 0;
};

// EKF-SLAM over an iSAM-format log (relative-point sightings, odometry with its own covariance).
struct IsamRunResult {
  Trajectory estimate;  // one pose per log pose, t = the pose's index in the file
  std::vector<Eigen::Matrix3d> pose_covariance;  // the filter's after each step (x, y, θ)
  LandmarkMap map;
  // About 50 snapshots of the map, evenly over the run, the final map last (for the viewer).
  std::vector<LandmarkMapSnapshot> map_history;
  int sightings = 0;
  int dropped = 0;
  int sightings_outside_gate = 0;  // matched no landmark: started one or dropped
  // Whether the re-observations missed their gates as often as the noise model allows (EKF
  // runs: a FastSLAM particle's gate holds one step's pose uncertainty, not the path's, so its
  // misses say less about the noise).
  std::optional<InnovationCheck> innovation_check;
  // Share of sightings whose landmark is the one the file names, after matching our landmarks
  // one-to-one to the file's ids (greedily, by the number of sightings each pair shares).
  double association_agreement = 0.0;
  // The same against the file's ids with each group of `reference_merges` taken as one landmark
  // (with score_against_merged_reference; else 0 and empty).
  double association_agreement_merged = 0.0;
  std::vector<std::vector<LandmarkId>> reference_merges;
  // The file's odometry (as written, before odometry_heading_drift_rad_per_m) against the
  // estimate: the drift to configure. Unset for a log shorter than one window.
  std::optional<HeadingDriftFit> odometry_heading_drift;
  std::optional<IsamReferenceErrors> smoothed_reference;  // with compare_with_smoothed_reference
  // Why the log could not be smoothed (the run is kept; smoothed_reference is then unset).
  std::string smoothed_reference_failure;
  double wall_time_s = 0.0;  // the SLAM pass alone
  std::vector<FilterCounter> counters;  // the filter's (LandmarkSlamFilter::Counters)
};

// EKF-SLAM (params.ekf) with the odometry and relative-point models.
IsamRunResult RunEkfSlamOnIsam(const IsamLog& log, const IsamRunParams& params);
// FastSLAM (`fastslam`: proposal, particles, threads; its association is set here) with the same
// models: known association as params.ekf says, otherwise each particle's by
// params.fastslam.new_landmark_test with params.fastslam's gates, the EKF's where unset.
IsamRunResult RunFastSlamOnIsam(const IsamLog& log, const IsamRunParams& params,
                                FastSlamParams fastslam);
// `fastslam` (proposal, particles, threads, seed) with the association and sampling settings
// RunFastSlamOnIsam gives it from `params`.
FastSlamParams IsamFastSlamParams(const IsamRunParams& params, FastSlamParams fastslam);
// Any point-landmark filter whose motion model takes the file's increments (dx, dy, dθ) as its
// control and whose sensor takes the sightings as they are (x forward, y left); the file's ids
// are given to it only with `known_association`. params.ekf is used for the merged reference only.
IsamRunResult RunFilterOnIsam(LandmarkSlamFilter& filter, const IsamLog& log,
                              const IsamRunParams& params, bool known_association);

// The file's landmark ids that its own data cannot tell apart, in groups (each sorted, groups by
// their first id): an EKF pass with the file's association and `params`' noise, then every pair
// of landmarks whose difference is within the association gate (squared Mahalanobis distance
// under their joint covariance) and that the file never sights from one pose. A program that
// wrote the file may have given one tree two ids (lost it, then started it again): scored
// one-to-one, a filter that maps that tree once would lose the smaller id's sightings.
std::vector<std::vector<LandmarkId>> IndistinguishableReferenceIds(const IsamLog& log,
                                                                   const IsamRunParams& params);

// std::invalid_argument (from SmoothLandmarkSlam) if the log cannot be smoothed.
IsamSmoothedReference SmoothIsamLog(const IsamLog& log, const IsamRunParams& params);

}  // namespace slamkit
