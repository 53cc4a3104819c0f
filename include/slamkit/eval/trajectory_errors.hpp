#pragma once

#include <span>
#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/core/relation.hpp"

namespace slamkit {

// Mean ± standard deviation (population) of the translational and absolute rotational errors of
// the relations (Kümmerle et al., "On measuring the accuracy of SLAM algorithms", 2009).
struct RelationErrorStats {
  int count = 0;
  double trans_mean_m = 0.0;
  double trans_std_m = 0.0;
  double rot_mean_deg = 0.0;
  double rot_std_deg = 0.0;
};

// For each relation, the estimated relative pose δ = x(t1)⁻¹ ⊕ x(t2) is compared with the
// reference δ*: the error is δ*⁻¹ ⊕ δ, its translation norm and |rotation| are averaged. Poses are
// looked up by timestamp (nearest within `time_tolerance_s`); a relation whose time has no pose
// throws std::invalid_argument naming it. Poses need not be in time order.
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

// Index of the pose nearest to `t_s` within the tolerance, or -1 (binary search).
int FindPoseAt(const Trajectory& trajectory, double t_s, double time_tolerance_s);

}  // namespace slamkit
