#include "slamkit/filters/ekf_slam/point_landmarks.hpp"

#include <algorithm>

#include "slamkit/filters/ekf/observation_model.hpp"

namespace slamkit {

void PointLandmarkMap::Clear() {
  blocks_.clear();
  source_ids_.clear();
  index_of_id_.clear();
}

int PointLandmarkMap::Add(int block, LandmarkId source_id) {
  const int index = size();
  blocks_.push_back(block);
  source_ids_.push_back(source_id);
  if (source_id != kNoLandmark) index_of_id_.emplace(source_id, index);
  return index;
}

int PointLandmarkMap::WithSourceId(LandmarkId id) const {
  const auto it = index_of_id_.find(id);
  return it == index_of_id_.end() ? -1 : it->second;
}

// The sightings against the current posterior, seen from pose block `observer`. The posterior
// does not change while the associator runs: the observer's pose, its covariance and the reach
// gate are computed here once for all sightings and candidates.
class PointSightings::Context final : public AssociationContext {
 public:
  Context(const PointSightings& s, const BlockEkf& ekf, int observer)
      : s_(s),
        ekf_(ekf),
        observer_(observer),
        pose_(ekf.PoseOf(observer)),
        P_pose_(ekf.PoseCovarianceOf(observer)),
        gate_(s.parts_.model->GateFrom(pose_)) {}

  int NumObservations() const override { return s_.NumSightings(); }
  const PointObservation& Observation(int i) const override { return s_.sightings_[i]; }
  int NumLandmarks() const override { return s_.map_->size(); }
  std::span<const AssociationCandidate> Candidates(int i) const override {
    std::vector<AssociationCandidate>& candidates = s_.map_->candidate_scratch();
    candidates.clear();
    for (int l = 0; l < NumLandmarks(); ++l) {
      // Outside a compressed area nothing is within reach (ActiveArea): skip the O(a) mean.
      const int block = s_.map_->Block(l);
      if (Taken(l) || !ekf_.IsActive(block) || !gate_.Passes(ekf_.Mean(block))) continue;
      candidates.push_back({l, Distance(i, l)});
    }
    return candidates;
  }
  int LandmarkWithSourceId(LandmarkId id) const override { return s_.map_->WithSourceId(id); }
  double Distance(int i, int landmark) const override {
    return PosePointDistance(ekf_, *s_.parts_.model, observer_, s_.map_->Block(landmark),
                             s_.sightings_[i], pose_, P_pose_);
  }
  JointInnovation Joint(std::span<const Pairing> hypothesis) const override {
    std::vector<Linearisation> parts;
    JointInnovation joint;
    for (const Pairing& p : hypothesis) parts.push_back(Linearised(p.observation, p.landmark));
    joint.nu.resize(2 * static_cast<int>(parts.size()));
    for (std::size_t k = 0; k < parts.size(); ++k) joint.nu.segment<2>(2 * k) = parts[k].innovation;
    joint.S = ekf_.JointInnovationCovariance(parts);
    return joint;
  }

 private:
  bool Taken(int l) const {
    const std::vector<char>& taken = *s_.taken_;
    return static_cast<std::size_t>(l) < taken.size() && taken[l];
  }
  Linearisation Linearised(int i, int landmark) const {
    const int blocks[] = {observer_, s_.map_->Block(landmark)};
    const PointObservation& obs = s_.sightings_[i];
    return Linearise(*s_.parts_.model, ekf_, blocks, obs.z, obs.R);
  }

  const PointSightings& s_;
  const BlockEkf& ekf_;
  int observer_;
  Pose2 pose_;
  Eigen::Matrix3d P_pose_;
  PointLandmarkModel::ReachGate gate_;
};

PointSightings::PointSightings(const PointLandmarkParts& parts, PointLandmarkMap& map,
                               std::span<const PointObservation> sightings,
                               const std::vector<char>& taken)
    : parts_(parts), map_(&map), sightings_(sightings), taken_(&taken) {}

std::vector<AssociationDecision> PointSightings::Associate(const BlockEkf& ekf, int observer) {
  return parts_.associator->Associate(Context(*this, ekf, observer));
}

MatchedObservation PointSightings::Matched(int observer, int sighting, int landmark) const {
  const PointObservation& obs = sightings_[sighting];
  return {parts_.update_model, {observer, map_->Block(landmark)}, 2, obs.z, obs.R};
}

int PointSightings::Augment(BlockEkf& ekf, int observer, int sighting) {
  return AddPointLandmark(ekf, *parts_.model, *map_, observer, sightings_[sighting]);
}

void MarkTaken(std::span<const AssociationDecision> decisions, std::vector<char>& taken) {
  for (const AssociationDecision& d : decisions) {
    if (d.landmark < 0) continue;
    taken.resize(std::max<std::size_t>(taken.size(), d.landmark + 1), 0);
    taken[d.landmark] = 1;
  }
}

// The generic MahalanobisSquared(Linearise()) of the point model, at fixed sizes.
double PosePointDistance(const BlockEkf& ekf, const PointLandmarkModel& model, int observer,
                         int point, const PointObservation& obs, const Pose2& x,
                         const Eigen::Matrix3d& P_pose) {
  PosePointObservation o;
  o.pose = observer;
  o.point = point;
  o.R = &obs.R;
  o.P_pose = &P_pose;
  model.LinearisePosePoint(x, ekf.Mean(point), obs.z, o);
  return ekf.MahalanobisSquaredPosePoint(o);
}

// SPEC S2, Eq. 8 (the inverse sensor model from the observer's pose).
int AddPointLandmark(BlockEkf& ekf, const PointLandmarkModel& model, PointLandmarkMap& map,
                     int observer, const PointObservation& obs) {
  const int observers[] = {observer};
  const int block = AugmentFrom(model, ekf, observers, obs.z, obs.R);
  return map.Add(block, obs.id);
}

}  // namespace slamkit
