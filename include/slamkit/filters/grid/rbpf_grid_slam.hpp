#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/state_health.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/filters/grid/gaussian_proposal.hpp"
#include "slamkit/filters/grid/grid_map_view.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"
#include "slamkit/filters/grid_slam.hpp"
#include "slamkit/filters/particles/particle_set.hpp"
#include "slamkit/filters/particles/particle_streams.hpp"
#include "slamkit/filters/particles/path_tree.hpp"
#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/models/odometry_sampling.hpp"

namespace slamkit {

// The matcher that tracks scans between updates. Its guesses are odometry-close (one scan's
// motion from the previous tracked pose), so it skips the coarse pass and starts with small
// steps; a tight prior on translation keeps it from sliding along corridors whose ends are not
// mapped yet (docs/grid_defaults.md, "Tracking between updates").
inline ScanMatcherParams TrackingMatcherParams() {
  ScanMatcherParams params;
  params.coarse_pass = false;
  params.linear_step_m = 0.02;
  params.angular_step_rad = 0.02;
  params.refinements = 3;
  params.prior_sigma_xy_m = 0.01;
  return params;
}

// Where a particle's pose at an update comes from once its motion sample is matched.
enum class ProposalScheme {
  // A draw from the Gaussian fitted around the scan match, weighted by its normaliser (Grisetti et
  // al. 2007).
  kGaussian,
  // The match itself, weighted by the scan likelihood there (ROS GMapping's shortcut).
  kScanMatch,
};

// What the scans between updates do. They never touch the particles, but each gets a pose.
enum class TrackingMode {
  // Each is matched against the best particle's map (one match per scan, not per particle),
  // starting from the previous scan's pose moved by odometry, and the particles then move by that
  // tracked motion (the best particle's last tracked pose plus one odometry step) instead of raw
  // odometry: a better prior where odometry drifts in heading.
  kTrackedMotion,
  // Tracked as above, but the particles move by raw odometry.
  kTrackOnly,
  // Poses by odometry alone from the last update (GMapping's output); particles by odometry.
  kOff,
};

// Particle i's context at an update, for an extra weight factor.
struct GridWeightContext {
  int particle;
  const Pose2& pose;         // the particle's pose after the proposal
  const GridMapView& map;    // its map (and second layer) as the proposal read it
  const ScanPoints& points;  // the scan's matched beams, robot frame
};

// An extra factor on the particles' weights: the log of what multiplies a particle's weight at an
// update, added after the scan likelihood (P-SLAM's p(z_u | x, h), SPEC S4 Eqs. 21-22). It is
// called for every particle at every update from several threads at once.
using GridWeightFactor = std::function<double(const GridWeightContext&)>;

struct RbpfGridSlamParams {
  int particles = 30;
  std::uint64_t seed = 1;
  // The filter updates once the odometry has moved this far since its last update (GMapping's
  // linearUpdate and angularUpdate); scans in between only extend the trajectory.
  double linear_update_m = 1.0;
  double angular_update_rad = 0.5;
  // Resample when N_eff / N falls below resampling.threshold (0.5), systematically by default.
  ResamplingParams resampling;
  // Log-likelihoods are multiplied by gain / particles before normalising (GMapping's ogain = 3
  // gives gain 1/3): it smooths the weights so that one scan does not decide the whole set.
  double likelihood_gain = 1.0 / 3.0;
  // Odometry noise (srr [m/m], srt [m/rad], str [rad/m], stt [rad/rad]); why str is 0.02 rad/m:
  // docs/grid_defaults.md.
  OdometryNoiseParams motion{.srr = 0.05, .srt = 0.05, .str = 0.02, .stt = 0.05};
  // A calibration of the log's odometry: each step between scans turns by this times its
  // distance more than the log says (a steering or wheel-radius offset turns a wheel odometry by a
  // bias proportional to the distance, which noise covers badly over a long loop). `slamkit grid`
  // reports the value its own estimate suggests (odometry_heading_drift in metrics.json).
  double odometry_heading_drift_rad_per_m = 0.0;
  // Estimates that drift as the filter runs, with the value above as its prior (off: the value
  // is used as is). After each update, the best particle's turn since the last one against the
  // log's odometry's, regressed on the distance driven (least squares); the prior weighs as much
  // as `heading_drift_prior_m2` of squared distance (50: fifty updates of 1 m).
  bool estimate_heading_drift = false;
  double heading_drift_prior_m2 = 50.0;
  // The laser's usable range, the one setting of it: beams longer than this are cut when they go
  // into the maps (free space only) and are matched neither by the particles nor by the tracking.
  double usable_range_m = 50.0;
  // Whether a scan's free-space update spares the cells its own returns hit (ScanInsertionParams):
  // beams grazing a wall no longer erode the wall cells their neighbours hit.
  bool misses_spare_scan_hits = true;
  // How far a no-return beam marks free space (ScanInsertionParams); infinity: the usable range.
  double no_return_ray_length_m = std::numeric_limits<double>::infinity();
  ScanMatcherParams matcher;
  // At an update, a particle's match that scores below this fraction of the particles' mean
  // score at the previous update is retried from other headings (matcher.widen_heading_*), where
  // matcher.widen_below_score_fraction is 0. A score relative to the log's own keeps the retries
  // to the poor matches of each building, whatever its typical score (open halls score lower).
  // Zero switches it off.
  double widen_below_typical_score = 0.0;
  ProposalScheme proposal = ProposalScheme::kGaussian;
  // Where each particle's scan match starts at an update: for this fraction of the particles
  // (drawn at each update), at a draw of the motion model (GMapping's code); for the others, at
  // the odometry prediction x_{t-1} ⊕ u_{t-1} without noise (Grisetti et al. 2007, Table 1,
  // step 2), where the motion noise shapes only the proposal and the weight. A prediction-started
  // match that leaves a direction unconstrained is made again from the draw, which keeps the
  // motion model's spread there (KeepConstrainedPart).
  double sampled_start_fraction = 0.0;
  // Each prediction-started match first sweeps its heading over this many standard deviations
  // of the motion model's heading noise (matcher.heading_sweep_rad); 0: no sweep.
  double heading_sweep_sigmas = 0.0;
  GaussianProposalParams gaussian;
  TrackingMode tracking_mode = TrackingMode::kTrackedMotion;
  ScanMatcherParams tracking = TrackingMatcherParams();
  // A tracked pose further than this from its odometry guess is a slide (along a corridor, into
  // unmapped space) rather than a correction: the guess is kept.
  double tracking_max_correction_m = 0.1;
  double tracking_max_correction_rad = 0.1;
  // A scan this far or further from the one before it (by odometry) is an update whatever the
  // thresholds above: the tracking is meant for dense scans, and between sparse ones (a scan a
  // metre, as the CARMEN suite's logs) the odometry can misjudge a turn by more than the
  // tracking's gates accept, which then carries the error into the next update's start.
  // Infinity: never.
  double tracking_max_step_m = 0.5;
  double tracking_max_step_rad = 0.25;
  OccupancyGridParams grid;
  // The pose of the first scan: the map and the trajectory are in this frame (the origin by
  // default; the log's first odometry pose keeps the log's frame).
  Pose2 initial_pose;
  // When the particles' health is checked (finite poses; log-weights finite or −∞, not all −∞,
  // normalising to 1): after every update in Debug and sanitizer builds, at output in Release.
  // O(particles), so the every-update cost is negligible; the covariance tolerances are unused.
  StateHealthParams health;
};

// One particle of RbpfGridSlam.
struct GridParticle {
  Pose2 pose;
  OccupancyGrid map;  // shares unchanged tiles with its copies
  PathTree path;      // its pose at each update
  // Consulted where `map` is unknown (P-SLAM's predicted structure); null: none. Kept by copies.
  std::shared_ptr<const OccupancyGrid> second_layer;

  GridMapView View() const { return {map, second_layer.get()}; }
};

// Rao-Blackwellised particle filter on occupancy grids (GMapping-like; SPEC S4): each particle
// holds a pose, a log-weight, its own map and its path (ParticleSet, PathTree). The proposal is a
// motion sample (the tracked motion or odometry) refined by scan matching against the particle's
// map view, then (kGaussian) drawn from the Gaussian fitted around the match; weights come from
// the scan likelihood there, times the optional extra factor; resampling is adaptive on N_eff.
// Maps share unchanged tiles (copy-on-write), so resampling copies are cheap. Particles are
// processed in parallel; each draws from its own stream (ParticleStreams), so a seed fixes the
// result whatever the thread count.
class RbpfGridSlam final : public GridSlam {
 public:
  explicit RbpfGridSlam(const RbpfGridSlamParams& params, GridWeightFactor extra_factor = {});
  ~RbpfGridSlam() override;

  // Takes the next scan (with its odometry); returns whether the filter updated on it.
  bool ProcessScan(const LaserScan& scan) override;
  // The odometry heading drift in use: the configured one, or its running estimate.
  double heading_drift_rad_per_m() const { return heading_drift_rad_per_m_; }

  int particle_count() const { return particles_.size(); }
  const GridParticle& particle(int i) const { return particles_[i]; }
  // Which particle of the previous update particle i was copied from by this update's
  // resampling (i itself when it did not resample).
  int particle_source(int i) const { return particles_.source(i); }
  // Sets particle i's second map layer (kept by its copies at resampling). Not during ProcessScan.
  void SetSecondLayer(int i, std::shared_ptr<const OccupancyGrid> layer);

  int BestParticle() const;
  const OccupancyGrid& BestMap() const override;
  // The best particle's path: one pose per processed scan (t = the scan's); a scan between updates
  // is placed relative to the particle's pose at the last update as it was tracked. Scans since
  // the last update are tracked here if the next update has not done it yet.
  Trajectory BestTrajectory() override;
  Pose2 CurrentPose() override;
  int updates() const { return updates_; }
  int resamples() const { return resamples_; }
  double last_neff() const { return particles_.last_neff(); }
  // The particles' health (see RbpfGridSlamParams::health) and the tracked poses of the scans,
  // unless health.mode is kOff; NumericalError naming the particle or scan if it fails.
  void CheckOutputHealth() const override;
  GridSlamStats Stats() const override {
    return {.updates = updates_,
            .resamples = resamples_,
            .heading_drift_in_use_rad_per_m = heading_drift_rad_per_m_,
            .graph = std::nullopt};
  }

 private:
  bool ProcessCalibratedScan(const LaserScan& scan);
  Pose2 CalibratedOdometry(const Pose2& raw, bool first);
  void UpdateHeadingDrift(bool first);
  ScanInsertionParams Insertion() const {
    return {.usable_range_m = params_.usable_range_m,
            .misses_spare_scan_hits = params_.misses_spare_scan_hits,
            .no_return_ray_length_m = params_.no_return_ray_length_m};
  }
  void Initialise(const LaserScan& scan);
  void MoveAndWeigh(const LaserScan& scan, const Pose2& delta);
  double MoveParticle(int i, const ScanPoints& points, const Pose2& delta,
                      const ScanMatcherParams& matcher);
  MatchResult MatchFromStart(const GridMapView& map, const ScanPoints& points,
                             const Pose2& previous, const Pose2& delta, const Pose2& sampled,
                             const ScanMatcherParams& matcher, Rng& rng) const;
  void ResampleIfNeeded();
  void InsertIntoMaps(const LaserScan& scan, int scan_index);
  void TrackAndMove(const LaserScan& scan, int scan_index, const Pose2& odometry_delta);
  void TrackPending(const GridMapView& map, const Pose2& anchor);
  void FinishTracking();
  void CheckParticleHealth(const std::string& where) const;

  RbpfGridSlamParams params_;
  GridWeightFactor extra_factor_;
  ParticleStreams streams_;
  ParticleSet<GridParticle> particles_;
  struct ScanRecord {
    double t_s;
    Pose2 odometry;
    Pose2 since_update;  // the scan's pose relative to the particles' poses at
                         // the last update
  };
  std::vector<ScanRecord> scans_;
  // Scans since the last update, waiting to be tracked (points empty without tracking).
  struct PendingScan {
    int scan_index;
    ScanPoints points;
  };
  std::vector<PendingScan> pending_;
  Pose2 last_update_odometry_;
  // The log's odometry at the last scan, and the calibrated chain's (odometry_heading_drift).
  Pose2 last_raw_odometry_;
  Pose2 last_calibrated_odometry_;
  // The drift in use, and estimate_heading_drift's sums (Σ d², Σ d·turn error) and anchor.
  double heading_drift_rad_per_m_ = 0.0;
  double drift_sum_dd_ = 0.0;
  double drift_sum_de_ = 0.0;
  Pose2 last_update_raw_odometry_;
  int updates_ = 0;
  int resamples_ = 0;
  double typical_score_fraction_ = 0.0;  // the particles' mean match score / beams, last update
};

}  // namespace slamkit
