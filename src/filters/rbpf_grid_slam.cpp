#include "slamkit/filters/rbpf_grid_slam.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include "slamkit/filters/resampling.hpp"

namespace slamkit {

struct RbpfGridSlam::PathNode {
  int scan_index;
  Pose2 pose;
  std::shared_ptr<const PathNode> parent;
};

struct RbpfGridSlam::Particle {
  Pose2 pose;
  double log_weight = 0.0;        // since the last resampling
  double path_log_weight = 0.0;   // over the whole path: picks the best particle (kept on copy)
  OccupancyGrid map;
  std::shared_ptr<const PathNode> path;  // shared by copies made in resampling
  int source = 0;                        // the particle it was copied from at the last resampling
};

RbpfGridSlam::RbpfGridSlam(const RbpfGridSlamParams& params)
    : params_(params), rng_(Rng::ForStream(params.seed, 0)) {}

RbpfGridSlam::~RbpfGridSlam() = default;

void RbpfGridSlam::Initialise(const LaserScan& scan) {
  Particle first;
  first.map = OccupancyGrid(params_.grid);
  InsertScan(first.map, first.pose.Compose(scan.laser_offset), scan, params_.insertion);
  first.path = std::make_shared<PathNode>(PathNode{0, first.pose, nullptr});
  particles_.assign(std::max(params_.particles, 1), first);  // copies share the map's tiles
  last_update_odometry_ = scan.odometry;
}

bool RbpfGridSlam::ProcessScan(const LaserScan& scan) {
  const int scan_index = static_cast<int>(scans_.size());
  scans_.push_back({scan.t_s, scan.odometry, Pose2()});
  if (scan_index == 0) {
    Initialise(scan);
    return true;
  }
  const Pose2 delta = last_update_odometry_.Between(scan.odometry);
  if (delta.translation().norm() < params_.linear_update_m &&
      std::abs(delta.theta()) < params_.angular_update_rad) {
    pending_.push_back({scan_index, params_.track_between_updates
                                        ? PrepareScan(scan, params_.tracking)
                                        : ScanPoints{}});
    return false;
  }
  TrackAndMove(scan, scan_index, delta);
  ResampleIfNeeded();
  InsertIntoMaps(scan, scan_index);
  last_update_odometry_ = scan.odometry;
  ++updates_;
  return true;
}

// Brings the tracking of the scans since the last update up to date and moves the particles:
// by the tracked motion (the last tracked pose plus one odometry step) when it is used, else by
// `odometry_delta`, with the tracking then running alongside.
void RbpfGridSlam::TrackAndMove(const LaserScan& scan, int scan_index,
                                const Pose2& odometry_delta) {
  if (params_.track_between_updates && params_.motion_from_tracking) {
    FinishTracking();
    const ScanRecord& previous = scans_[scan_index - 1];
    MoveAndWeigh(scan, previous.since_update.Compose(previous.odometry.Between(scan.odometry)));
    return;
  }
  // The particles write only their poses and weights while they move, never their maps.
  const Particle& best = particles_[BestParticle()];
  tbb::task_group tracking;
  tracking.run([this, &map = best.map, anchor = best.pose] { TrackPending(map, anchor); });
  MoveAndWeigh(scan, odometry_delta);
  tracking.wait();
}

// SPEC S4 (GMapping's proposal): sample the motion, refine it by matching the scan
// against the particle's own map, weigh by the scan likelihood at the refined pose.
void RbpfGridSlam::MoveAndWeigh(const LaserScan& scan, const Pose2& delta) {
  const ScanPoints points = PrepareScan(scan, params_.matcher);
  const int n = static_cast<int>(particles_.size());
  tbb::parallel_for(0, n, [&](int i) {
    Particle& p = particles_[i];
    Rng rng = Rng::ForStream(params_.seed, 1 + std::uint64_t(updates_) * n + i);
    const Pose2 previous = p.pose;
    const Pose2 predicted = SampleOdometryMotion(previous, delta, params_.motion, rng);
    const MatchResult match = MatchScan(p.map, points, predicted, params_.matcher);
    double log_likelihood = 0.0;
    if (!match.accepted) {
      p.pose = predicted;
      log_likelihood = EvaluatePose(p.map, points, predicted, params_.matcher).log_likelihood;
    } else if (params_.gaussian_proposal) {
      const ProposalDistribution proposal =
          GaussianProposal(p.map, points, match.pose, previous, delta, params_.motion,
                           params_.matcher, params_.proposal);
      p.pose = SampleProposal(proposal, rng);
      log_likelihood = proposal.log_normaliser;
    } else {
      p.pose = match.pose;
      log_likelihood = match.quality.log_likelihood;
    }
    p.log_weight += log_likelihood;
    p.path_log_weight += log_likelihood;
  });
}

// The scans between updates leave the particles where they are; each one's pose relative to
// the last update is tracked against the best particle's map (`map`, with that particle's pose
// `anchor`), which is much closer to the truth than odometry over up to a metre: on Intel the
// rotational error of the relations is dominated by these scans otherwise.
void RbpfGridSlam::TrackPending(const OccupancyGrid& map, const Pose2& anchor) {
  for (const PendingScan& pending : pending_) {
    const ScanRecord& previous = scans_[pending.scan_index - 1];
    ScanRecord& current = scans_[pending.scan_index];
    Pose2 since = previous.since_update.Compose(previous.odometry.Between(current.odometry));
    if (params_.track_between_updates) {
      const Pose2 guess = anchor.Compose(since);
      const MatchResult match = MatchScan(map, pending.points, guess, params_.tracking);
      const Pose2 correction = guess.Between(match.pose);
      if (match.accepted &&
          correction.translation().norm() <= params_.tracking_max_correction_m &&
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
  const Particle& best = particles_[BestParticle()];
  TrackPending(best.map, best.pose);
}

void RbpfGridSlam::ResampleIfNeeded() {
  std::vector<double> log_weights;
  for (const Particle& p : particles_) log_weights.push_back(p.log_weight);
  const double gain = params_.likelihood_gain / double(particles_.size());
  const std::vector<double> weights = NormaliseLogWeights(log_weights, gain);
  last_neff_ = EffectiveSampleSize(weights);
  for (std::size_t i = 0; i < particles_.size(); ++i) particles_[i].source = int(i);
  if (last_neff_ >= params_.resample_threshold * double(particles_.size())) return;
  const std::vector<int> keep = SystematicResample(weights, rng_);
  std::vector<Particle> next;
  next.reserve(particles_.size());
  for (int k : keep) {
    next.push_back(particles_[k]);
    next.back().log_weight = 0.0;
    next.back().source = k;
  }
  particles_.swap(next);
  ++resamples_;
}

// Copies of one particle hold the same pose and map: the scan goes into the first copy once and
// the others share its tiles. The other copies let go of their maps first, so that tiles shared
// only among copies are written in place instead of being copied and then dropped.
void RbpfGridSlam::InsertIntoMaps(const LaserScan& scan, int scan_index) {
  const int n = static_cast<int>(particles_.size());
  std::vector<int> first_of_source(n, -1), owners;
  for (int i = 0; i < n; ++i) {
    int& first = first_of_source[particles_[i].source];
    if (first < 0) {
      first = i;
      owners.push_back(i);
    } else {
      particles_[i].map = OccupancyGrid(params_.grid);
    }
  }
  tbb::parallel_for(0, static_cast<int>(owners.size()), [&](int k) {
    Particle& p = particles_[owners[k]];
    InsertScan(p.map, p.pose.Compose(scan.laser_offset), scan, params_.insertion);
    p.path = std::make_shared<PathNode>(PathNode{scan_index, p.pose, p.path});
  });
  for (int i = 0; i < n; ++i) {
    const int first = first_of_source[particles_[i].source];
    if (first != i) {
      particles_[i].map = particles_[first].map;
      particles_[i].path = particles_[first].path;
    }
  }
}

int RbpfGridSlam::BestParticle() const {
  int best = 0;
  for (int i = 1; i < static_cast<int>(particles_.size()); ++i) {
    if (particles_[i].path_log_weight > particles_[best].path_log_weight) best = i;
  }
  return best;
}

const OccupancyGrid& RbpfGridSlam::BestMap() const { return particles_[BestParticle()].map; }

Pose2 RbpfGridSlam::CurrentPose() {
  FinishTracking();
  if (particles_.empty()) return Pose2();
  const Particle& p = particles_[BestParticle()];
  return p.pose.Compose(scans_.back().since_update);
}

Trajectory RbpfGridSlam::BestTrajectory() {
  FinishTracking();
  Trajectory out(scans_.size());
  if (particles_.empty()) return out;
  std::vector<const PathNode*> nodes;
  for (const PathNode* n = particles_[BestParticle()].path.get(); n; n = n->parent.get()) {
    nodes.push_back(n);
  }
  std::reverse(nodes.begin(), nodes.end());
  std::size_t k = 0;
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    while (k + 1 < nodes.size() && nodes[k + 1]->scan_index <= int(i)) ++k;
    out[i] = {scans_[i].t_s, nodes[k]->pose.Compose(scans_[i].since_update)};
  }
  return out;
}

}  // namespace slamkit
