#include "slamkit/runners/landmark/landmark_run.hpp"

#include <chrono>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "slamkit/eval/alignment.hpp"

namespace slamkit {
namespace {

using Clock = std::chrono::steady_clock;

// Landmark error after the best rigid alignment of the estimated map onto the true one, pairing
// each estimated landmark with the true landmark of the sighting that created it.
double AlignedMapRmse(const LandmarkMap& map, const LandmarkWorld& world) {
  std::unordered_map<LandmarkId, Eigen::Vector2d> truth;
  for (const Landmark& l : world.landmarks) truth.emplace(l.id, l.position_m);
  std::vector<Eigen::Vector2d> from, to;
  for (const MappedLandmark& m : map.landmarks) {
    const auto it = truth.find(m.source_id);
    if (it == truth.end()) continue;
    from.push_back(m.position_m);
    to.push_back(it->second);
  }
  return AlignPoints(from, to).rmse_m;
}

AssociationOutcome OutcomeOf(AssociationDecision::Kind kind) {
  switch (kind) {
    case AssociationDecision::Kind::kMatched: return AssociationOutcome::kMatched;
    case AssociationDecision::Kind::kNew: return AssociationOutcome::kNew;
    case AssociationDecision::Kind::kDropped: break;
  }
  return AssociationOutcome::kDropped;
}

// Joins the filter's decisions with the truth, in filter order: each landmark's true id is that
// of the sighting that created it, and each sighting is scored against the true id of the
// landmark it matched. Returns the true id of each landmark (by index; kNoLandmark where no
// decision created it).
std::vector<LandmarkId> JoinWithTruth(
    const std::vector<std::vector<AssociationDecision>>& scans,
    const std::vector<std::vector<LandmarkId>>& scan_true_ids, int num_landmarks,
    AssociationScorer& scorer) {
  std::vector<LandmarkId> landmark_truth(static_cast<std::size_t>(num_landmarks), kNoLandmark);
  for (std::size_t s = 0; s < scans.size(); ++s) {
    for (std::size_t i = 0; i < scans[s].size(); ++i) {
      const AssociationDecision& d = scans[s][i];
      const LandmarkId true_id = scan_true_ids[s][i];
      const bool names_landmark = d.kind != AssociationDecision::Kind::kDropped;
      if (names_landmark && (d.landmark < 0 || d.landmark >= num_landmarks)) {
        throw std::logic_error("RunLandmarkFilter: a decision names landmark " +
                               std::to_string(d.landmark) + " of a map of " +
                               std::to_string(num_landmarks));
      }
      if (d.kind == AssociationDecision::Kind::kNew) landmark_truth[d.landmark] = true_id;
      const LandmarkId matched = d.kind == AssociationDecision::Kind::kMatched
                                     ? landmark_truth[d.landmark]
                                     : kNoLandmark;
      scorer.Add(true_id, OutcomeOf(d.kind), matched);
    }
  }
  return landmark_truth;
}

std::vector<AssociationDecision> CheckedUpdate(LandmarkSlamFilter& filter,
                                               std::span<const PointObservation> observations) {
  std::vector<AssociationDecision> decisions = filter.Update(observations);
  if (decisions.size() != observations.size()) {
    throw std::logic_error("RunLandmarkFilter: " + std::to_string(decisions.size()) +
                           " decisions for " + std::to_string(observations.size()) +
                           " observations");
  }
  return decisions;
}

}  // namespace

LandmarkRunRecorder::LandmarkRunRecorder(LandmarkSlamFilter& filter, bool known_association)
    : filter_(filter), known_association_(known_association) {}

const std::vector<AssociationDecision>& LandmarkRunRecorder::Start(
    const Pose2& initial_pose, const StampedPose& truth,
    const std::vector<PointObservation>& observations, const std::vector<LandmarkId>& true_ids) {
  filter_.Reset(initial_pose, Eigen::Matrix3d::Zero());
  Record(CheckedUpdate(filter_, Given(observations, true_ids)), true_ids);
  out_.truth.push_back(truth);
  out_.estimate.push_back({0.0, filter_.PoseEstimate()});
  if (snapshots_ > 0) Snapshot(0.0);
  return decisions_.back();
}

const std::vector<AssociationDecision>& LandmarkRunRecorder::Step(
    const SimStep& step, double dt_s, const StampedPose& truth,
    const std::vector<LandmarkId>& true_ids) {
  const std::span<const PointObservation> given = Given(step.observations, true_ids);
  const auto start = Clock::now();
  filter_.Predict(step.control, dt_s);
  std::vector<AssociationDecision> decisions = CheckedUpdate(filter_, given);
  out_.step_time_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  Record(std::move(decisions), true_ids);
  const Pose2 estimate = filter_.PoseEstimate();
  const Eigen::Vector3d e = PoseError(estimate, truth.pose);
  out_.errors.push_back(e);
  const Eigen::Matrix3d covariance = filter_.PoseCovariance();
  out_.nees.push_back(Nees(e, covariance));
  out_.pose_covariance.push_back(covariance);
  out_.estimate.push_back({step.t_s, estimate});
  out_.truth.push_back(truth);
  if (snapshots_ > 0 && ++steps_ % snapshot_every_ == 0) Snapshot(step.t_s);
  return decisions_.back();
}

// Snapshots are taken every snapshot_every_ steps; at 2 × snapshots_ of them every other one is
// dropped and the spacing doubled, so a run of unknown length keeps an even history.
void LandmarkRunRecorder::Snapshot(double t_s) {
  std::vector<LandmarkMapSnapshot>& history = out_.map_history;
  history.push_back({t_s, filter_.Map()});
  if (history.size() < 2 * static_cast<std::size_t>(snapshots_)) return;
  for (std::size_t i = 0; 2 * i < history.size(); ++i) history[i] = std::move(history[2 * i]);
  history.resize((history.size() + 1) / 2);
  snapshot_every_ *= 2;
}

// The only place a true id can reach the filter, and only with known association.
std::span<const PointObservation> LandmarkRunRecorder::Given(
    const std::vector<PointObservation>& observations, const std::vector<LandmarkId>& true_ids) {
  if (true_ids.size() != observations.size()) {
    throw std::invalid_argument("RunLandmarkFilter: truth and inputs differ in length");
  }
  if (!known_association_) return observations;
  with_ids_ = observations;
  for (std::size_t i = 0; i < true_ids.size(); ++i) with_ids_[i].id = true_ids[i];
  return with_ids_;
}

void LandmarkRunRecorder::Record(std::vector<AssociationDecision> decisions,
                                 const std::vector<LandmarkId>& true_ids) {
  decisions_.push_back(std::move(decisions));
  true_ids_.push_back(true_ids);
}

RunResult LandmarkRunRecorder::Finish(const LandmarkWorld& world) {
  RunResult out = std::move(out_);
  filter_.Flush();
  out.counters = filter_.Counters();
  filter_.CheckOutputHealth();  // before the map, the one output still read from the state
  out.map = filter_.Map();
  AssociationScorer scorer;
  const std::vector<LandmarkId> landmark_truth = JoinWithTruth(
      decisions_, true_ids_, static_cast<int>(out.map.landmarks.size()), scorer);
  for (std::size_t i = 0; i < out.map.landmarks.size(); ++i) {
    out.map.landmarks[i].source_id = landmark_truth[i];
  }
  // Start took the first snapshot, and thinning keeps it.
  if (snapshots_ > 0 && out.map_history.back().t_s != out.estimate.back().t_s) {
    out.map_history.push_back({out.estimate.back().t_s, out.map});
  }
  // A landmark keeps its index for the filter's life, so the final join names it in every
  // snapshot.
  for (LandmarkMapSnapshot& snapshot : out.map_history) {
    for (std::size_t i = 0; i < snapshot.map.landmarks.size(); ++i) {
      snapshot.map.landmarks[i].source_id = landmark_truth[i];
    }
  }
  out.rmse = ComputePoseRmse(out.errors);
  out.map_rmse_m = AlignedMapRmse(out.map, world);
  out.association = scorer.score();
  return out;
}

}  // namespace slamkit
