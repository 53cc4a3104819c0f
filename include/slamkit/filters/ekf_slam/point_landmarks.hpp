#pragma once

#include <Eigen/Core>
#include <span>
#include <unordered_map>
#include <vector>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/ekf_slam/update_pipeline.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// The point landmarks of a BlockEkf, indexed by landmark (creation order): each one's block and
// the id of the sighting that created it (kNoLandmark if it had none).
class PointLandmarkMap {
 public:
  void Clear();
  // Landmark in block `block`, created from a sighting with id `source_id`; returns its index.
  int Add(int block, LandmarkId source_id);

  int size() const { return static_cast<int>(blocks_.size()); }
  int Block(int landmark) const { return blocks_[landmark]; }
  std::span<const int> Blocks() const { return blocks_; }
  LandmarkId SourceId(int landmark) const { return source_ids_[landmark]; }
  // The landmark created from sighting id `id`, or -1.
  int WithSourceId(LandmarkId id) const;
  // Scratch for association's candidate lists: a PointSightings lives for one observation on a
  // per-observation schedule, so a buffer of its own would be reallocated for each.
  std::vector<AssociationCandidate>& candidate_scratch() const { return candidate_scratch_; }

 private:
  std::vector<int> blocks_;
  std::vector<LandmarkId> source_ids_;
  std::unordered_map<LandmarkId, int> index_of_id_;
  mutable std::vector<AssociationCandidate> candidate_scratch_;
};

// What a filter's point landmarks are made of. All must outlive the PointSightings using them.
struct PointLandmarkParts {
  // Association (the reach gate, the Mahalanobis distance, joint tests) and augmentation, at the
  // current estimates.
  const PointLandmarkModel* model = nullptr;
  // The sequential updates: `model`, or one linearising elsewhere (FirstEstimatesPointModel).
  const ObservationModel* update_model = nullptr;
  Associator* associator = nullptr;
};

// The point-landmark kind of the update pipeline: `sightings` (a scan, or a part of it) against
// the landmarks of `map`, seen from the pipeline's observer. Landmarks marked in `taken`
// (indexed by landmark; shorter than the map where none beyond are taken) are no candidates: a
// landmark takes at most one sighting per scan, also across the parts of one.
class PointSightings final : public LandmarkSightings {
 public:
  PointSightings(const PointLandmarkParts& parts, PointLandmarkMap& map,
                 std::span<const PointObservation> sightings, const std::vector<char>& taken);

  int NumSightings() const override { return static_cast<int>(sightings_.size()); }
  std::vector<AssociationDecision> Associate(const BlockEkf& ekf, int observer) override;
  MatchedObservation Matched(int observer, int sighting, int landmark) const override;
  int Augment(BlockEkf& ekf, int observer, int sighting) override;

 private:
  class Context;

  PointLandmarkParts parts_;
  PointLandmarkMap* map_;
  std::span<const PointObservation> sightings_;
  const std::vector<char>* taken_;
};

// Marks every landmark `decisions` name as taken (growing `taken` as needed).
void MarkTaken(std::span<const AssociationDecision> decisions, std::vector<char>& taken);

// The squared Mahalanobis distance of `obs` from the point landmark in block `point` seen from
// pose block `observer`: MahalanobisSquared(Linearise(model, …)) at fixed sizes, with the
// observer's pose `x` and covariance `P_pose` supplied by the caller (association computes them
// once for all candidates).
double PosePointDistance(const BlockEkf& ekf, const PointLandmarkModel& model, int observer,
                         int point, const PointObservation& obs, const Pose2& x,
                         const Eigen::Matrix3d& P_pose);

// SPEC S2, Eq. 8: adds the point landmark `obs` shows from pose block `observer` to `ekf` and to
// `map`; returns its landmark index.
int AddPointLandmark(BlockEkf& ekf, const PointLandmarkModel& model, PointLandmarkMap& map,
                     int observer, const PointObservation& obs);

}  // namespace slamkit
