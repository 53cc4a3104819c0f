#include "slamkit/filters/features/feature_sightings.hpp"

#include "slamkit/filters/ekf/observation_model.hpp"

namespace slamkit {

// SPEC S1 (line association), seen from `observer`.
std::vector<AssociationDecision> LineSightings::Associate(const BlockEkf& ekf, int observer) {
  return associator_->Associate(ekf, observer, *model_, *map_, sightings_);
}

MatchedObservation LineSightings::Matched(int observer, int sighting, int landmark) const {
  const LineSegment& s = sightings_[sighting];
  return {model_, {observer, map_->Block(landmark)}, 2, LineVector(s.line), s.covariance};
}

// SPEC S2, Eq. 8 for a line; its extent starts as the sighting's segment, placed from the
// observer's pose.
int LineSightings::Augment(BlockEkf& ekf, int observer, int sighting) {
  const int observers[] = {observer};
  const LineSegment& s = sightings_[sighting];
  const int block = AugmentFrom(*model_, ekf, observers, LineVector(s.line), s.covariance);
  const Pose2 x = ekf.PoseOf(observer);
  return map_->Add(block, LineOf(ekf.Mean(block)), x.TransformFrom(s.start_m),
                   x.TransformFrom(s.end_m));
}

void CornerMap::Clear() {
  blocks_.clear();
  kinds_.clear();
}

int CornerMap::Add(int block, CornerKind kind) {
  blocks_.push_back(block);
  kinds_.push_back(kind);
  return size() - 1;
}

// The scan's corners against the corner landmarks from `observer`: a candidate must pass the
// reach gate and be of the sighting's kind (concave or convex), so the associator never pairs
// the two kinds.
class CornerSightings::Context final : public AssociationContext {
 public:
  Context(const CornerSightings& s, const BlockEkf& ekf, int observer)
      : s_(s), ekf_(ekf), observer_(observer) {}

  int NumObservations() const override { return s_.NumSightings(); }
  const PointObservation& Observation(int i) const override { return s_.observations_[i]; }
  int NumLandmarks() const override { return s_.map_->size(); }
  std::span<const AssociationCandidate> Candidates(int i) const override {
    candidates_.clear();
    for (int c = 0; c < NumLandmarks(); ++c) {
      const int blocks[] = {observer_, s_.map_->Block(c)};
      // Outside a compressed area no corner is within reach (FeatureEkfSlam's area).
      if (s_.map_->Kind(c) != s_.corners_[i].kind || !ekf_.IsActive(blocks[1])) continue;
      if (!s_.model_->Gate(ekf_, blocks)) continue;
      candidates_.push_back({c, Distance(i, c)});
    }
    return candidates_;
  }
  int LandmarkWithSourceId(LandmarkId /*id*/) const override { return -1; }
  double Distance(int i, int corner) const override {
    return ekf_.MahalanobisSquared(Linearised(i, corner));
  }
  JointInnovation Joint(std::span<const Pairing> hypothesis) const override {
    std::vector<Linearisation> parts;
    JointInnovation joint;
    joint.nu.resize(2 * static_cast<int>(hypothesis.size()));
    for (const Pairing& p : hypothesis) parts.push_back(Linearised(p.observation, p.landmark));
    for (std::size_t k = 0; k < parts.size(); ++k) joint.nu.segment<2>(2 * k) = parts[k].innovation;
    joint.S = ekf_.JointInnovationCovariance(parts);
    return joint;
  }

 private:
  Linearisation Linearised(int i, int corner) const {
    const int blocks[] = {observer_, s_.map_->Block(corner)};
    const PointObservation& obs = s_.observations_[i];
    return Linearise(*s_.model_, ekf_, blocks, obs.z, obs.R);
  }

  const CornerSightings& s_;
  const BlockEkf& ekf_;
  int observer_;
  mutable std::vector<AssociationCandidate> candidates_;
};

// SPEC S1: a corner is a point landmark seen in range-bearing.
CornerSightings::CornerSightings(const PointLandmarkModel& model, Associator& associator,
                                 CornerMap& map, std::span<const Corner> corners)
    : model_(&model), associator_(&associator), map_(&map), corners_(corners) {
  observations_.reserve(corners.size());
  for (const Corner& c : corners) {
    PointObservation obs;
    const RangeBearing rb = CornerRangeBearing(c, &obs.R);
    obs.z << rb.range_m, rb.bearing_rad;
    observations_.push_back(obs);
  }
}

std::vector<AssociationDecision> CornerSightings::Associate(const BlockEkf& ekf, int observer) {
  return associator_->Associate(Context(*this, ekf, observer));
}

MatchedObservation CornerSightings::Matched(int observer, int sighting, int landmark) const {
  const PointObservation& obs = observations_[sighting];
  return {model_, {observer, map_->Block(landmark)}, 2, obs.z, obs.R};
}

// SPEC S2, Eq. 8 for a corner (the inverse range-bearing model from the observer's pose).
int CornerSightings::Augment(BlockEkf& ekf, int observer, int sighting) {
  const int observers[] = {observer};
  const PointObservation& obs = observations_[sighting];
  const int block = AugmentFrom(*model_, ekf, observers, obs.z, obs.R);
  return map_->Add(block, corners_[sighting].kind);
}

}  // namespace slamkit
