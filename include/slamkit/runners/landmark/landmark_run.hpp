#pragma once

#include <span>
#include <vector>

#include "slamkit/core/ids.hpp"
#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {

// One landmark filter run fed step by step, as the steps happen (RunLandmarkFilter for a whole
// SimRun, the closed loop of active_run.hpp one step at a time): it keeps the filter's outputs
// and, beside them, the truth, and joins the two into a RunResult at the end. The filter gets a
// sighting's true id only with `known_association`.
class LandmarkRunRecorder {
 public:
  LandmarkRunRecorder(LandmarkSlamFilter& filter, bool known_association);

  // Resets the filter at `initial_pose` and gives it the scan seen from there.
  const std::vector<AssociationDecision>& Start(const Pose2& initial_pose,
                                                const StampedPose& truth,
                                                const std::vector<PointObservation>& observations,
                                                const std::vector<LandmarkId>& true_ids);
  // Predicts with the step's control over `dt_s`, updates with its scan and scores the pose
  // against `truth`. Returns the filter's decisions on the scan (valid until the next call).
  const std::vector<AssociationDecision>& Step(const SimStep& step, double dt_s,
                                               const StampedPose& truth,
                                               const std::vector<LandmarkId>& true_ids);
  // Checks the filter's health and joins its map and decisions with the truth. Throws
  // std::logic_error if the filter broke the interface.
  RunResult Finish(const LandmarkWorld& world);

 private:
  std::span<const PointObservation> Given(const std::vector<PointObservation>& observations,
                                          const std::vector<LandmarkId>& true_ids);
  void Record(std::vector<AssociationDecision> decisions, const std::vector<LandmarkId>& true_ids);

  LandmarkSlamFilter& filter_;
  bool known_association_;
  RunResult out_;
  // Every scan's decisions beside its true ids, joined at the end (the map's indices are stable).
  std::vector<std::vector<AssociationDecision>> decisions_;
  std::vector<std::vector<LandmarkId>> true_ids_;
  std::vector<PointObservation> with_ids_;  // the scan with its true ids (known association)
};

}  // namespace slamkit
