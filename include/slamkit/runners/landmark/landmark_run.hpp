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
  // Keeps between `count` and 2 × `count` snapshots of the filter's map (RunResult::map_history),
  // evenly over a run of any length, and the final map; 0 (the default): none. Reading the map
  // leaves the filter as it was.
  void KeepMapSnapshots(int count) { snapshots_ = count; }

 private:
  std::span<const PointObservation> Given(const std::vector<PointObservation>& observations,
                                          const std::vector<LandmarkId>& true_ids);
  void Record(std::vector<AssociationDecision> decisions, const std::vector<LandmarkId>& true_ids);
  void Snapshot(double t_s);

  LandmarkSlamFilter& filter_;
  bool known_association_;

  int snapshots_ = 0;
  int snapshot_every_ = 1;  // steps between snapshots, doubled whenever 2 × snapshots_ are held
  int steps_ = 0;
  RunResult out_;
  // Every scan's decisions beside its true ids, joined at the end (the map's indices are stable).
  std::vector<std::vector<AssociationDecision>> decisions_;
  std::vector<std::vector<LandmarkId>> true_ids_;
  std::vector<PointObservation> with_ids_;  // the scan with its true ids (known association)
};

}  // namespace slamkit
