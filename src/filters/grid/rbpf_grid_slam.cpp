#include "slamkit/filters/grid/rbpf_grid_slam.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "slamkit/core/angle.hpp"

namespace slamkit {

RbpfGridSlam::RbpfGridSlam(const RbpfGridSlamParams& params, GridWeightFactor extra_factor)
    : params_(params),
      extra_factor_(std::move(extra_factor)),
      streams_(params.seed, std::max(params.particles, 1)),
      heading_drift_rad_per_m_(params.odometry_heading_drift_rad_per_m) {}

RbpfGridSlam::~RbpfGridSlam() = default;

void RbpfGridSlam::Initialise(const LaserScan& scan) {
  GridParticle first;
  first.pose = params_.initial_pose;
  first.map = OccupancyGrid(params_.grid);
  InsertScan(first.map, first.pose.Compose(scan.laser_offset), scan, Insertion());
  first.path.Append(0, first.pose);
  particles_.Assign(params_.particles, first);  // copies share the map's tiles
  last_update_odometry_ = scan.odometry;
}

bool RbpfGridSlam::ProcessScan(const LaserScan& scan) {
  if (!params_.estimate_heading_drift && heading_drift_rad_per_m_ == 0.0) {
    return ProcessCalibratedScan(scan);
  }
  const bool first = scans_.empty();
  LaserScan calibrated = scan;
  calibrated.odometry = CalibratedOdometry(scan.odometry, first);
  const bool updated = ProcessCalibratedScan(calibrated);
  if (updated && params_.estimate_heading_drift) UpdateHeadingDrift(first);
  return updated;
}

// Least squares of the turn the odometry misses on the distance driven, one sample per update:
// the best particle's turn between its last two path poses (scan-matched, so locally close to
// the true turn) less the log's odometry's turn over the same scans.
void RbpfGridSlam::UpdateHeadingDrift(bool first) {
  const PathTree::Node* leaf = particles_[BestParticle()].path.leaf();
  if (!first && leaf != nullptr && leaf->parent != nullptr) {
    const Pose2 odometry = last_update_raw_odometry_.Between(last_raw_odometry_);
    const double distance_m = odometry.translation().norm();
    const double missed_rad =
        WrapAngle(leaf->parent->pose.Between(leaf->pose).theta() - odometry.theta());
    drift_sum_dd_ += distance_m * distance_m;
    drift_sum_de_ += distance_m * missed_rad;
    const double prior_m2 = params_.heading_drift_prior_m2;
    heading_drift_rad_per_m_ =
        (prior_m2 * params_.odometry_heading_drift_rad_per_m + drift_sum_de_) /
        (prior_m2 + drift_sum_dd_);
  }
  last_update_raw_odometry_ = last_raw_odometry_;
}

// The log's odometry chain with each step turned by odometry_heading_drift_rad_per_m × its
// distance; the first pose is the log's.
Pose2 RbpfGridSlam::CalibratedOdometry(const Pose2& raw, bool first) {
  if (first) {
    last_calibrated_odometry_ = raw;
  } else {
    const Pose2 step = last_raw_odometry_.Between(raw);
    const double turn = heading_drift_rad_per_m_ * step.translation().norm();
    last_calibrated_odometry_ =
        last_calibrated_odometry_.Compose(Pose2(step.x(), step.y(), step.theta() + turn));
  }
  last_raw_odometry_ = raw;
  return last_calibrated_odometry_;
}

bool RbpfGridSlam::ProcessCalibratedScan(const LaserScan& scan) {
  const int scan_index = static_cast<int>(scans_.size());
  scans_.push_back({scan.t_s, scan.odometry, Pose2()});
  if (scan_index == 0) {
    Initialise(scan);
    return true;
  }
  const Pose2 delta = last_update_odometry_.Between(scan.odometry);
  const Pose2 step = scans_[scan_index - 1].odometry.Between(scan.odometry);
  const bool dense = step.translation().norm() < params_.tracking_max_step_m &&
                     std::abs(step.theta()) < params_.tracking_max_step_rad;
  if (dense && delta.translation().norm() < params_.linear_update_m &&
      std::abs(delta.theta()) < params_.angular_update_rad) {
    pending_.push_back(
        {scan_index, params_.tracking_mode != TrackingMode::kOff
                         ? PrepareScan(scan, params_.usable_range_m, params_.tracking)
                         : ScanPoints{}});
    return false;
  }
  TrackAndMove(scan, scan_index, delta);
  if (params_.health.every_update()) {
    // Before resampling, which would replace a particle with a bad weight by a healthy copy. The
    // rest of the update moves no pose.
    CheckParticleHealth("RbpfGridSlam at update " + std::to_string(updates_ + 1) + " (scan " +
                        std::to_string(scan_index) + ")");
  }
  ResampleIfNeeded();
  InsertIntoMaps(scan, scan_index);
  last_update_odometry_ = scan.odometry;
  ++updates_;
  return true;
}

// The maps need no check: a cell is an 8-bit fixed-point log-odds, clamped, never non-finite.
void RbpfGridSlam::CheckParticleHealth(const std::string& where) const {
  for (int i = 0; i < particles_.size(); ++i) {
    CheckFinite(particles_[i].pose.vector(), "particle " + std::to_string(i) + "'s pose", where);
  }
  particles_.CheckHealth(params_.likelihood_gain / double(particles_.size()), where);
}

void RbpfGridSlam::CheckOutputHealth() const {
  if (!params_.health.enabled() || particles_.empty()) return;
  const std::string where = "RbpfGridSlam at output (update " + std::to_string(updates_) + ")";
  CheckParticleHealth(where);
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    CheckFinite(scans_[i].since_update.vector(), "scan " + std::to_string(i) + "'s tracked pose",
                where);
  }
}

// Brings the tracking of the scans since the last update up to date and moves the particles: by
// the tracked motion (the last tracked pose plus one odometry step) with kTrackedMotion, else by
// `odometry_delta`, with the tracking then running alongside.
void RbpfGridSlam::TrackAndMove(const LaserScan& scan, int scan_index,
                                const Pose2& odometry_delta) {
  if (params_.tracking_mode == TrackingMode::kTrackedMotion) {
    FinishTracking();
    const ScanRecord& previous = scans_[scan_index - 1];
    MoveAndWeigh(scan, previous.since_update.Compose(previous.odometry.Between(scan.odometry)));
    return;
  }
  // The particles write only their poses and weights while they move, never their maps.
  const GridParticle& best = particles_[BestParticle()];
  tbb::task_group tracking;
  tracking.run([this, map = best.View(), anchor = best.pose] { TrackPending(map, anchor); });
  MoveAndWeigh(scan, odometry_delta);
  tracking.wait();
}

// SPEC S4 (GMapping's proposal): every particle moves and is weighed (MoveParticle); their mean
// match score sets the next update's bar for a poor match (widen_below_typical_score).
void RbpfGridSlam::MoveAndWeigh(const LaserScan& scan, const Pose2& delta) {
  const ScanPoints points = PrepareScan(scan, params_.usable_range_m, params_.matcher);
  const int n = particles_.size();
  ScanMatcherParams matcher = params_.matcher;
  if (params_.widen_below_typical_score > 0.0) {
    matcher.widen_below_score_fraction =
        params_.widen_below_typical_score * typical_score_fraction_;
  }
  std::vector<double> scores(n, 0.0);
  tbb::parallel_for(0, n, [&](int i) { scores[i] = MoveParticle(i, points, delta, matcher); });
  double total = 0.0;
  for (double s : scores) total += s;  // in particle order: the same sum for any thread count
  typical_score_fraction_ = points.ends.empty() ? 0.0 : total / (n * double(points.ends.size()));
}

// Particle i's match at an update, from the start RbpfGridSlamParams::sampled_start_fraction
// picks for it: the motion draw `sampled` or the prediction `previous` ⊕ `delta`.
MatchResult RbpfGridSlam::MatchFromStart(const GridMapView& map, const ScanPoints& points,
                                         const Pose2& previous, const Pose2& delta,
                                         const Pose2& sampled, const ScanMatcherParams& matcher,
                                         Rng& rng) const {
  const double f = params_.sampled_start_fraction;
  const bool from_prediction = f <= 0.0 || (f < 1.0 && rng.Uniform() >= f);
  if (!from_prediction) return MatchScan(map, points, sampled, matcher);
  ScanMatcherParams swept = matcher;
  swept.heading_sweep_rad =
      params_.heading_sweep_sigmas * OdometryNoiseSigmas(delta, params_.motion).z();
  const MatchResult match = MatchScan(map, points, previous.Compose(delta), swept);
  if (match.constraints.unconstrained == 0) return match;
  return MatchScan(map, points, sampled, matcher);
}

// Samples particle i's motion, refines it by matching the scan against its own map (SPEC S4;
// Grisetti et al. 2007, Table 1), weighs it by the scan likelihood at the refined pose (and by
// the extra factor, if any); returns the match's score.
double RbpfGridSlam::MoveParticle(int i, const ScanPoints& points, const Pose2& delta,
                                  const ScanMatcherParams& matcher) {
  GridParticle& p = particles_[i];
  Rng rng = streams_.ForParticle(updates_, i);
  const GridMapView map = p.View();
  const Pose2 previous = p.pose;
  const Pose2 predicted = SampleOdometryMotion(previous, delta, params_.motion, rng);
  const MatchResult match = MatchFromStart(map, points, previous, delta, predicted, matcher, rng);
  double log_likelihood = 0.0;
  if (!match.accepted) {
    p.pose = predicted;
    log_likelihood = ScanLogLikelihood(map, points, predicted, params_.matcher);
  } else if (params_.proposal == ProposalScheme::kGaussian) {
    ProposalDistribution proposal = GaussianProposal(map, points, match.pose, previous, delta,
                                                     params_.motion, params_.matcher,
                                                     params_.gaussian);
    KeepConstrainedPart(match.constraints, match.pose, &proposal);
    p.pose = SampleProposal(proposal, rng);
    log_likelihood = proposal.log_normaliser;
  } else {
    p.pose = match.pose;
    log_likelihood = match.quality.log_likelihood;
  }
  particles_.AddLogWeight(i, log_likelihood);
  if (extra_factor_) particles_.AddLogWeight(i, extra_factor_({i, p.pose, map, points}));
  return match.quality.score;
}

// The scans between updates leave the particles where they are; each one's pose relative to the
// last update is tracked against the best particle's map (`map`, with that particle's pose
// `anchor`), which is much closer to the truth than odometry over up to a metre: on Intel the
// rotational error of the relations is dominated by these scans otherwise.
void RbpfGridSlam::TrackPending(const GridMapView& map, const Pose2& anchor) {
  const bool track = params_.tracking_mode != TrackingMode::kOff;
  for (const PendingScan& pending : pending_) {
    const ScanRecord& previous = scans_[pending.scan_index - 1];
    ScanRecord& current = scans_[pending.scan_index];
    Pose2 since = previous.since_update.Compose(previous.odometry.Between(current.odometry));
    if (track) {
      const Pose2 guess = anchor.Compose(since);
      const MatchResult match = MatchScan(map, pending.points, guess, params_.tracking);
      const Pose2 correction = guess.Between(match.pose);
      if (match.accepted && correction.translation().norm() <= params_.tracking_max_correction_m &&
          std::abs(correction.theta()) <= params_.tracking_max_correction_rad) {
        since = anchor.Between(match.pose);
      }
    }
    current.since_update = since;
  }
  pending_.clear();
}

void RbpfGridSlam::FinishTracking() {
  if (pending_.empty() || particles_.empty()) return;
  const GridParticle& best = particles_[BestParticle()];
  TrackPending(best.View(), best.pose);
}

void RbpfGridSlam::ResampleIfNeeded() {
  const double gain = params_.likelihood_gain / double(particles_.size());
  if (particles_.ResampleIfNeeded(gain, params_.resampling, streams_.filter())) ++resamples_;
}

// Copies of one particle hold the same pose and map: the scan goes into the first copy once and
// the others share its tiles. The other copies let go of their maps first, so that tiles shared
// only among copies are written in place instead of being copied and then dropped.
void RbpfGridSlam::InsertIntoMaps(const LaserScan& scan, int scan_index) {
  const int n = particles_.size();
  std::vector<int> first_of_source(n, -1), owners;
  for (int i = 0; i < n; ++i) {
    int& first = first_of_source[particles_.source(i)];
    if (first < 0) {
      first = i;
      owners.push_back(i);
    } else {
      particles_[i].map = OccupancyGrid(params_.grid);
    }
  }
  const ScanInsertionParams insertion = Insertion();
  tbb::parallel_for(0, static_cast<int>(owners.size()), [&](int k) {
    GridParticle& p = particles_[owners[k]];
    InsertScan(p.map, p.pose.Compose(scan.laser_offset), scan, insertion);
    p.path.Append(scan_index, p.pose);
  });
  for (int i = 0; i < n; ++i) {
    const int first = first_of_source[particles_.source(i)];
    if (first != i) {
      particles_[i].map = particles_[first].map;
      particles_[i].path = particles_[first].path;
    }
  }
}

void RbpfGridSlam::SetSecondLayer(int i, std::shared_ptr<const OccupancyGrid> layer) {
  particles_[i].second_layer = std::move(layer);
}

int RbpfGridSlam::BestParticle() const { return particles_.Best(); }

const OccupancyGrid& RbpfGridSlam::BestMap() const {
  if (particles_.empty()) throw std::logic_error("RbpfGridSlam::BestMap: no scan processed yet");
  return particles_[BestParticle()].map;
}

Pose2 RbpfGridSlam::CurrentPose() {
  FinishTracking();
  if (particles_.empty()) return Pose2();
  const GridParticle& p = particles_[BestParticle()];
  return p.pose.Compose(scans_.back().since_update);
}

Trajectory RbpfGridSlam::BestTrajectory() {
  FinishTracking();
  Trajectory out(scans_.size());
  if (particles_.empty()) return out;
  const std::vector<const PathTree::Node*> nodes = particles_[BestParticle()].path.Walk();
  std::size_t k = 0;
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    while (k + 1 < nodes.size() && nodes[k + 1]->step <= int(i)) ++k;
    out[i] = {scans_[i].t_s, nodes[k]->pose.Compose(scans_[i].since_update)};
  }
  return out;
}

}  // namespace slamkit
