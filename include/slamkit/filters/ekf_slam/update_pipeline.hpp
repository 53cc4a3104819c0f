#pragma once

#include <span>
#include <vector>

#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/selection/selection.hpp"

namespace slamkit {

// One kind of landmark (points, lines, corners, …) as one scan sees it: the scan's sightings of
// that kind, how they are associated with the kind's landmarks, the update each matched one
// makes and the landmark each new one starts. `observer` is always the BlockEkf pose block the
// scan was taken from, so a kind works for any vehicle whose pose the state holds.
class LandmarkSightings {
 public:
  virtual ~LandmarkSightings() = default;

  virtual int NumSightings() const = 0;
  // One decision per sighting, in order, against the current posterior of `ekf`; kNew decisions
  // carry landmark -1.
  virtual std::vector<AssociationDecision> Associate(const BlockEkf& ekf, int observer) = 0;
  // Sighting `sighting` as the update of landmark `landmark` (its model, the blocks it involves,
  // observer first, z and R).
  virtual MatchedObservation Matched(int observer, int sighting, int landmark) const = 0;
  // SPEC S2, Eq. 8: adds the landmark that sighting `sighting` shows from `observer` to `ekf`
  // and to the kind's map; returns its landmark index.
  virtual int Augment(BlockEkf& ekf, int observer, int sighting) = 0;
};

// One scan's EKF update from pose block `observer`, over the sightings of several landmark
// kinds: association of each kind against the prior, one selection step over the matched
// sightings of all kinds together (kinds in the order given, each kind's sightings in scan
// order), their sequential updates, then augmentation by the new sightings in the same order.
// Run() does the three steps; a filter with work of its own between them (FeatureEkfSlam's line
// extents) calls them one by one, in order, once each. The updates stay deferred: applying the
// downdate is the caller's.
class UpdatePipeline {
 public:
  // `ekf` and the kinds must outlive the pipeline.
  UpdatePipeline(BlockEkf& ekf, int observer, std::span<LandmarkSightings* const> kinds);

  // Step 1: each kind's decisions against the current posterior.
  void Associate();
  // Steps 2 and 3 (SPEC S1 items 1 and 3): `policy` chooses which matched sightings update the
  // filter, and in what order, on a BlockSelectionSession (`diagnostics`: see
  // BlockSelectionSession). What it did; all zero, with no session, if nothing matched.
  SelectionStats SelectAndUpdate(SelectionPolicy& policy, bool diagnostics);
  // Step 4: a landmark for every sighting association called new; its decision then names it.
  void Augment();
  // The three steps in order.
  SelectionStats Run(SelectionPolicy& policy, bool diagnostics);

  int observer() const { return observer_; }
  // Kind `kind`'s decisions (after Associate(); after Augment() the new ones name their landmark).
  const std::vector<AssociationDecision>& Decisions(int kind) const { return decisions_[kind]; }

 private:
  std::vector<MatchedObservation> Matched() const;

  BlockEkf* ekf_;
  int observer_;
  std::span<LandmarkSightings* const> kinds_;
  std::vector<std::vector<AssociationDecision>> decisions_;  // by kind
};

}  // namespace slamkit
