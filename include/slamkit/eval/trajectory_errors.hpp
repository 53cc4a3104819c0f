#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "slamkit/core/relation.hpp"
#include "slamkit/core/trajectory.hpp"

namespace slamkit {

// Mean ± standard deviation (population) of the translational and absolute rotational errors of
// the relations (Kümmerle et al., "On measuring the accuracy of SLAM algorithms", 2009).
struct RelationErrorStats {
  int count = 0;    // relations scored
  int skipped = 0;  // relations with a time before the first or after the last pose
  double trans_mean_m = 0.0;
  double trans_std_m = 0.0;
  double rot_mean_deg = 0.0;
  double rot_std_deg = 0.0;
};

// For each relation, the estimated relative pose δ = x(t1)⁻¹ ⊕ x(t2) is compared with the
// reference δ*: the error is δ*⁻¹ ⊕ δ, its translation norm and |rotation| are averaged. Poses are
// looked up by timestamp (InterpolatePoseAt: the nearest within `time_tolerance_s`, else
// interpolated between the poses either side); a relation with a time outside the trajectory is
// skipped and counted; if every relation is skipped (relations of another log),
// std::invalid_argument naming both time spans. Poses need not be in time order.
RelationErrorStats EvaluateRelations(const Trajectory& estimate,
                                     std::span<const PoseRelation> relations,
                                     double time_tolerance_s = 1e-3);

// The relations both of whose times have a pose in `trajectory` (for runs over part of a log).
std::vector<PoseRelation> RelationsCovered(const Trajectory& trajectory,
                                           std::span<const PoseRelation> relations,
                                           double time_tolerance_s = 1e-3);

// Absolute trajectory error: positions of `estimate` and `reference` paired by timestamp (nearest
// within `time_tolerance_s`, unpaired poses skipped), the best rigid alignment of the estimate
// onto the reference, then the RMS, mean and max of the remaining position errors.
struct AbsoluteTrajectoryErrorStats {
  int count = 0;
  double rmse_m = 0.0;
  double mean_m = 0.0;
  double max_m = 0.0;
};

AbsoluteTrajectoryErrorStats AbsoluteTrajectoryError(const Trajectory& estimate,
                                                     const Trajectory& reference,
                                                     double time_tolerance_s = 1e-3);

// An estimate compared pose for pose with a reference of the same scans in the same order (for
// logs whose timestamps cannot pair them, such as csail-corrected's 6-digit ones): ATE after the
// best rigid alignment, and the relations metric on the pairs (i, i + step) of the reference.
struct ReferenceComparison {
  AbsoluteTrajectoryErrorStats ate;
  RelationErrorStats rpe;
};

ReferenceComparison CompareWithReference(const Trajectory& estimate, const Trajectory& reference,
                                         int step = 1);

// Index of the pose nearest to `t_s` within the tolerance, or -1 (binary search on a trajectory
// in time order).
int FindPoseAt(const Trajectory& trajectory, double t_s, double time_tolerance_s);

// The pose at `t_s` on a trajectory in time order: the nearest pose within `time_tolerance_s`,
// else the interpolation between the poses either side (position linear in time, heading along
// the shorter arc); nullopt before the first or after the last pose.
std::optional<Pose2> InterpolatePoseAt(const Trajectory& trajectory, double t_s,
                                       double time_tolerance_s);

// How an estimate's poses are paired with a reference's.
enum class PairBy {
  kTime,   // nearest timestamp within a tolerance (unpaired poses are left out)
  kIndex,  // pose i with pose i: the same scans in the same order, whatever the clock says
};

// CompareWithReference after pairing by `pair_by`. By time, each reference pose is paired with the
// estimated pose nearest in time within `time_tolerance_s`; RPE is then over consecutive pairs.
// Throws std::invalid_argument when nothing pairs, or by index when the sizes differ.
ReferenceComparison CompareWithReference(const Trajectory& estimate, const Trajectory& reference,
                                         PairBy pair_by, double time_tolerance_s = 1e-3);

// Why `trajectory`'s timestamps cannot pair poses (repeated or decreasing times, beyond
// `time_tolerance_s`), or "" when they can: a reference or log whose stamps fail this must be
// paired by index.
std::string TimestampProblem(const Trajectory& trajectory, double time_tolerance_s = 1e-3);

// `trajectory` with strictly increasing times, as TUM readers (evo) require: each time that is
// not at least `min_step_s` after the previous (written) one becomes that one + `min_step_s`, so
// good stretches keep their stamps and a jitter or a run of equal stamps is pushed forward by
// microseconds. `moved` (optional) counts the poses whose time changed.
Trajectory WithIncreasingTimes(const Trajectory& trajectory, double min_step_s = 1e-6,
                               int* moved = nullptr);

}  // namespace slamkit
