#include "slamkit/filters/fastslam/fastslam.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "fastslam_steps.hpp"
#include "slamkit/core/state_health.hpp"

namespace slamkit {

using fastslam_detail::ParticleUpdate;

FastSlam::FastSlam(const FastSlamParams& params, std::unique_ptr<MotionModel> motion,
                   std::unique_ptr<PointSensorModel> sensor)
    : params_(params),
      motion_(std::move(motion)),
      sensor_(std::move(sensor)),
      streams_(params.seed, std::max(params.particles, 1)) {
  if (!motion_ || !sensor_) throw std::invalid_argument("FastSlam: no motion or sensor model");
  if (params_.particles < 1) throw std::invalid_argument("FastSlam: particles must be >= 1");
  if (!(params_.index_cell_m > 0.0)) throw std::invalid_argument("FastSlam: index_cell_m <= 0");
  if (params_.delayed_sampling && (params_.known_association || params_.negative_evidence)) {
    throw std::invalid_argument(
        "FastSlam: delayed_sampling needs each particle's own association, without negative "
        "evidence");
  }
  if (params_.window_max_landmarks < 1) {
    throw std::invalid_argument("FastSlam: window_max_landmarks must be >= 1");
  }
  Reset(Pose2(), Eigen::Matrix3d::Zero());
}

// Each particle's work reads only shared inputs and writes only its own slots, and draws from its
// own stream (ParticleStreams), so the result does not depend on the thread count.
template <class F>
void FastSlam::ForEachParticle(F&& f) {
  const int n = particles_.size();
  if (params_.threads <= 1) {
    for (int k = 0; k < n; ++k) f(k);
    return;
  }
  tbb::task_arena arena(params_.threads);
  arena.execute([&] { tbb::parallel_for(0, n, [&](int k) { f(k); }); });
}

void FastSlam::Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) {
  FastSlamParticle first;
  first.pose = pose;
  if (params_.delayed_sampling && params_.proposal == FastSlamProposal::kObservation) {
    first.window_covariance = Eigen::Matrix3d::Zero();
  }
  particles_.Assign(params_.particles, first);
  streams_ = ParticleStreams(params_.seed, particles_.size());
  step_ = 0;
  resampled_ = false;
  updated_ = false;
  before_resampling_.reset();
  slot_source_ids_.clear();
  slot_of_id_.clear();
  slot_grid_.clear();
  index_of_slot_.clear();
  slot_of_index_.clear();
  last_named_.clear();
  if (!pose_cov.isZero(0.0)) {
    ForEachParticle([&](int k) {
      Rng rng = streams_.ForParticle(step_, k);
      particles_[k].pose = Pose2(pose.vector() + Eigen::Vector3d(rng.MultivariateNormal(pose_cov)));
    });
  }
  ++step_;
}

void FastSlam::Predict(const Control& u, double dt_s, const ControlCovariance* control_noise) {
  if (!u.allFinite() || !std::isfinite(dt_s) || (control_noise && !control_noise->allFinite())) {
    throw std::invalid_argument("FastSlam::Predict: non-finite control, time step or noise");
  }
  const ControlCovariance Q = control_noise ? *control_noise : motion_->Noise(u, dt_s);
  const int step = step_++;
  before_resampling_.reset();
  ForEachParticle([&](int k) {
    Rng rng = streams_.ForParticle(step, k);
    fastslam_detail::PredictParticle(particles_[k], *motion_, params_.proposal, u, dt_s, Q, rng);
  });
}

std::vector<AssociationDecision> FastSlam::Update(std::span<const PointObservation> observations) {
  for (const PointObservation& obs : observations) {
    if (!obs.z.allFinite() || !obs.R.allFinite()) {
      throw std::invalid_argument("FastSlam::Update: non-finite measurement or covariance");
    }
  }
  const int step = step_++;
  const fastslam_detail::ScanInputs scan{params_, *sensor_, observations, slot_grid_, slot_of_id_};
  updates_.resize(static_cast<std::size_t>(particles_.size()));
  ForEachParticle([&](int k) {
    Rng rng = streams_.ForParticle(step, k);
    fastslam_detail::UpdateParticle(particles_[k], scan, rng, updates_[k]);
  });
  const std::vector<int> slot_of_observation = AllocateSlots(observations, updates_);
  ForEachParticle([&](int k) {
    fastslam_detail::InsertCreated(particles_[k], updates_[k], slot_of_observation);
    particles_.AddLogWeight(k, updates_[k].log_weight);
  });
  updated_ = true;
  std::vector<AssociationDecision> decisions = Report(updates_, slot_of_observation);
  // Montemerlo et al. 2003, Sec. 5 (after Doucet et al.): resample only when the weights have
  // degenerated, low-variance sampling by default (Probabilistic Robotics Table 4.4).
  const Pose2 mean = WeightedMean();
  before_resampling_.emplace(mean, WeightedSpread(mean));
  resampled_ = particles_.ResampleIfNeeded(1.0, params_.resampling, streams_.filter());
  if (!resampled_) before_resampling_.reset();
  return decisions;
}

int FastSlam::NewSlot(const Eigen::Vector2d& position, LandmarkId source_id) {
  const int slot = static_cast<int>(slot_source_ids_.size());
  slot_source_ids_.push_back(source_id);
  index_of_slot_.push_back(-1);
  slot_grid_[fastslam_detail::CellKey(position, params_.index_cell_m)].push_back(slot);
  if (params_.known_association && source_id != kNoLandmark) slot_of_id_[source_id] = slot;
  return slot;
}

// A sighting gets a slot when at least one particle mapped it as new, in scan order, so slots
// do not depend on which thread ran which particle. With known association an id keeps its slot
// (a particle that lost the landmark to negative evidence maps it there again). The grid files
// the slot where the first such particle put it.
std::vector<int> FastSlam::AllocateSlots(std::span<const PointObservation> observations,
                                         const std::vector<ParticleUpdate>& updates) {
  std::vector<int> slot_of_observation(observations.size(), -1);
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const ParticleUpdate* creator = nullptr;
    for (const ParticleUpdate& u : updates) {
      if (u.decisions[i].kind == AssociationDecision::Kind::kNew) {
        creator = &u;
        break;
      }
    }
    if (creator == nullptr) continue;
    const auto known = params_.known_association ? slot_of_id_.find(observations[i].id)
                                                 : slot_of_id_.end();
    slot_of_observation[i] = known != slot_of_id_.end()
                                 ? known->second
                                 : NewSlot(creator->created[i].mean, observations[i].id);
  }
  return slot_of_observation;
}

int FastSlam::IndexOf(int slot) {
  int& index = index_of_slot_[slot];
  if (index < 0) {
    index = static_cast<int>(slot_of_index_.size());
    slot_of_index_.push_back(slot);
    last_named_.emplace_back();
  }
  return index;
}

MappedLandmark FastSlam::Mapped(int slot, const FastSlamLandmark& l) const {
  return {slot_source_ids_[slot], l.mean, l.covariance};
}

// The decisions of the particle with the largest total weight after the scan, with slots turned
// into landmark indexes (see the class comment).
std::vector<AssociationDecision> FastSlam::Report(const std::vector<ParticleUpdate>& updates,
                                                  const std::vector<int>& slot_of_observation) {
  const int best = particles_.Best();
  std::vector<AssociationDecision> decisions = updates[best].decisions;
  for (std::size_t i = 0; i < decisions.size(); ++i) {
    AssociationDecision& d = decisions[i];
    if (d.kind == AssociationDecision::Kind::kNew) d.landmark = slot_of_observation[i];
    if (d.landmark < 0) continue;
    const int slot = d.landmark;
    d.landmark = IndexOf(slot);
    FastSlamLandmark scratch;
    if (const FastSlamLandmark* l = Find(particles_[best], slot, scratch)) {
      last_named_[d.landmark] = Mapped(slot, *l);
    }
  }
  return decisions;
}

void FastSlam::AddLandmarks(const LandmarkMap& map) {
  if (updated_) throw std::logic_error("FastSlam::AddLandmarks: only before the first Update()");
  LandmarkTree<FastSlamLandmark> tree = particles_[0].landmarks;
  for (const MappedLandmark& m : map.landmarks) {
    const int slot = NewSlot(m.position_m, m.source_id);
    tree.Set(slot, {m.position_m, m.covariance, 1});
    last_named_[IndexOf(slot)] = m;
  }
  for (int k = 0; k < particles_.size(); ++k) particles_[k].landmarks = tree;
}

Pose2 FastSlam::PoseEstimate() const {
  return before_resampling_ ? before_resampling_->first : WeightedMean();
}

Eigen::Matrix3d FastSlam::PoseCovariance() const {
  return before_resampling_ ? before_resampling_->second : WeightedSpread(WeightedMean());
}

Pose2 FastSlam::WeightedMean() const {
  const std::vector<double> w = particles_.Weights();
  double x = 0.0, y = 0.0, s = 0.0, c = 0.0;
  for (int k = 0; k < particles_.size(); ++k) {
    const Pose2& p = particles_[k].pose;
    x += w[k] * p.x();
    y += w[k] * p.y();
    s += w[k] * std::sin(p.theta());
    c += w[k] * std::cos(p.theta());
  }
  return Pose2(x, y, std::atan2(s, c));  // the heading's mean direction on the circle
}

Eigen::Matrix3d FastSlam::WeightedSpread(const Pose2& mean) const {
  const std::vector<double> w = particles_.Weights();
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  for (int k = 0; k < particles_.size(); ++k) {
    const Eigen::Vector3d d = PoseError(particles_[k].pose, mean);
    P += w[k] * (d * d.transpose() + particles_[k].pose_covariance);
  }
  return P;
}

LandmarkMap FastSlam::Map() const {
  const FastSlamParticle& best = particles_[particles_.Best()];
  LandmarkMap map;
  map.landmarks.reserve(slot_of_index_.size());
  FastSlamLandmark scratch;
  for (std::size_t i = 0; i < slot_of_index_.size(); ++i) {
    const FastSlamLandmark* l = Find(best, slot_of_index_[i], scratch);
    map.landmarks.push_back(l ? Mapped(slot_of_index_[i], *l) : last_named_[i]);
  }
  best.landmarks.ForEach([&](int slot, const FastSlamLandmark& l) {
    if (index_of_slot_[slot] < 0) map.landmarks.push_back(Mapped(slot, l));
  });
  for (const FastSlamParticle::WindowLandmark& w : best.window) {
    if (w.slot >= 0 && index_of_slot_[w.slot] < 0 && Find(best, w.slot, scratch)) {
      map.landmarks.push_back(Mapped(w.slot, scratch));
    }
  }
  return map;
}

const FastSlamLandmark* FastSlam::Find(const FastSlamParticle& p, int slot,
                                       FastSlamLandmark& scratch) {
  if (const FastSlamLandmark* l = p.landmarks.Get(slot)) return l;
  for (std::size_t j = 0; j < p.window.size(); ++j) {
    if (p.window[j].slot != slot) continue;
    const int at = 3 + 2 * static_cast<int>(j);
    scratch.mean = p.window[j].mean;
    scratch.covariance = p.window_covariance.block<2, 2>(at, at);
    return &scratch;
  }
  return nullptr;
}

void FastSlam::CheckOutputHealth() const {
  const std::string where = "FastSlam at output";
  particles_.CheckHealth(1.0, where);
  for (int k = 0; k < particles_.size(); ++k) {
    CheckFinite(particles_[k].pose.vector(), "particle " + std::to_string(k) + " pose", where);
  }
  const StateHealthParams health;
  particles_[particles_.Best()].landmarks.ForEach([&](int slot, const FastSlamLandmark& l) {
    CheckGaussianHealth(l.mean, l.covariance, health, true,
                        where + ", best particle's landmark slot " + std::to_string(slot));
  });
}

}  // namespace slamkit
