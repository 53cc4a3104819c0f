#pragma once

#include <span>
#include <vector>

#include "slamkit/features/corners.hpp"
#include "slamkit/features/line_extraction.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/ekf_slam/update_pipeline.hpp"
#include "slamkit/filters/features/line_association.hpp"
#include "slamkit/filters/features/line_landmark_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// The line kind of the update pipeline (SPEC S1): a scan's line sightings (robot frame) against
// the line landmarks of `map`, associated by `associator` under `model`. A new line's extent is
// its sighting's segment placed from the observer's pose. All must outlive the sightings.
class LineSightings final : public LandmarkSightings {
 public:
  LineSightings(const LineAssociator& associator, const LineLandmarkModel& model, LineMap& map,
                std::span<const LineSegment> sightings)
      : associator_(&associator), model_(&model), map_(&map), sightings_(sightings) {}

  int NumSightings() const override { return static_cast<int>(sightings_.size()); }
  std::vector<AssociationDecision> Associate(const BlockEkf& ekf, int observer) override;
  MatchedObservation Matched(int observer, int sighting, int landmark) const override;
  int Augment(BlockEkf& ekf, int observer, int sighting) override;

 private:
  const LineAssociator* associator_;
  const LineLandmarkModel* model_;
  LineMap* map_;
  std::span<const LineSegment> sightings_;
};

// The corner landmarks of a BlockEkf, indexed by corner (creation order): each one's block and
// its concave/convex kind, kept beside the block as an association constraint.
class CornerMap {
 public:
  void Clear();
  // Corner in block `block` of kind `kind`; returns its index.
  int Add(int block, CornerKind kind);

  int size() const { return static_cast<int>(blocks_.size()); }
  int Block(int corner) const { return blocks_[corner]; }
  CornerKind Kind(int corner) const { return kinds_[corner]; }

 private:
  std::vector<int> blocks_;
  std::vector<CornerKind> kinds_;
};

// The corner kind of the update pipeline (SPEC S1): a scan's corners (robot frame) as point
// landmarks seen in range-bearing (CornerRangeBearing) under `model`, against the corners of
// `map`. `associator` is offered only the corners of a sighting's kind that pass the model's
// gate. All must outlive the sightings.
class CornerSightings final : public LandmarkSightings {
 public:
  CornerSightings(const PointLandmarkModel& model, Associator& associator, CornerMap& map,
                  std::span<const Corner> corners);

  int NumSightings() const override { return static_cast<int>(corners_.size()); }
  std::vector<AssociationDecision> Associate(const BlockEkf& ekf, int observer) override;
  MatchedObservation Matched(int observer, int sighting, int landmark) const override;
  int Augment(BlockEkf& ekf, int observer, int sighting) override;

 private:
  class Context;

  const PointLandmarkModel* model_;
  Associator* associator_;
  CornerMap* map_;
  std::span<const Corner> corners_;
  std::vector<PointObservation> observations_;  // the corners in range-bearing
};

}  // namespace slamkit
