#include "slamkit/eval/trajectory_errors.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/eval/alignment.hpp"

namespace slamkit {
namespace {

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

MeanStd Summarise(const std::vector<double>& values) {
  if (values.empty()) return {};
  double sum = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / double(values.size());
  double sq = 0.0;
  for (double v : values) sq += (v - mean) * (v - mean);
  return {mean, std::sqrt(sq / double(values.size()))};
}

const Pose2& PoseAt(const Trajectory& trajectory, double t_s, double tolerance_s) {
  const int i = FindPoseAt(trajectory, t_s, tolerance_s);
  if (i < 0) {
    throw std::invalid_argument(
        fmt::format("no estimated pose within {} s of relation time {:.6f}", tolerance_s, t_s));
  }
  return trajectory[i].pose;
}

// Logs whose clock jitters (intel.clf) give trajectories slightly out of time order.
Trajectory SortedByTime(const Trajectory& trajectory) {
  Trajectory sorted = trajectory;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.t_s < b.t_s; });
  return sorted;
}

}  // namespace

int FindPoseAt(const Trajectory& trajectory, double t_s, double time_tolerance_s) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t_s,
                                   [](const StampedPose& p, double t) { return p.t_s < t; });
  int best = -1;
  double best_dt = time_tolerance_s;
  for (auto c : {it, it == trajectory.begin() ? it : std::prev(it)}) {
    if (c == trajectory.end()) continue;
    const double dt = std::abs(c->t_s - t_s);
    if (dt <= best_dt) {
      best_dt = dt;
      best = static_cast<int>(c - trajectory.begin());
    }
  }
  return best;
}

// Kümmerle et al. 2009, Eq. 2 with the translational and rotational parts kept apart.
RelationErrorStats EvaluateRelations(const Trajectory& unsorted_estimate,
                                     std::span<const PoseRelation> relations,
                                     double time_tolerance_s) {
  const Trajectory estimate = SortedByTime(unsorted_estimate);
  std::vector<double> trans, rot;
  trans.reserve(relations.size());
  rot.reserve(relations.size());
  for (const PoseRelation& r : relations) {
    const Pose2 delta = PoseAt(estimate, r.t1_s, time_tolerance_s)
                            .Between(PoseAt(estimate, r.t2_s, time_tolerance_s));
    const Pose2 error = r.delta.Between(delta);
    trans.push_back(error.translation().norm());
    rot.push_back(RadToDeg(std::abs(error.theta())));
  }
  const MeanStd t = Summarise(trans), a = Summarise(rot);
  return {static_cast<int>(relations.size()), t.mean, t.std, a.mean, a.std};
}

std::vector<PoseRelation> RelationsCovered(const Trajectory& trajectory,
                                           std::span<const PoseRelation> relations,
                                           double time_tolerance_s) {
  const Trajectory sorted = SortedByTime(trajectory);
  std::vector<PoseRelation> out;
  for (const PoseRelation& r : relations) {
    if (FindPoseAt(sorted, r.t1_s, time_tolerance_s) >= 0 &&
        FindPoseAt(sorted, r.t2_s, time_tolerance_s) >= 0) {
      out.push_back(r);
    }
  }
  return out;
}

AbsoluteTrajectoryErrorStats AbsoluteTrajectoryError(const Trajectory& unsorted_estimate,
                                                     const Trajectory& reference,
                                                     double time_tolerance_s) {
  const Trajectory estimate = SortedByTime(unsorted_estimate);
  std::vector<Eigen::Vector2d> from, to;
  for (const StampedPose& ref : reference) {
    const int i = FindPoseAt(estimate, ref.t_s, time_tolerance_s);
    if (i < 0) continue;
    from.push_back(estimate[i].pose.translation());
    to.push_back(ref.pose.translation());
  }
  AbsoluteTrajectoryErrorStats out;
  out.count = static_cast<int>(from.size());
  if (from.empty()) return out;
  const RigidAlignment alignment = AlignPoints(from, to);
  for (std::size_t k = 0; k < from.size(); ++k) {
    const double e = (alignment.transform.TransformFrom(from[k]) - to[k]).norm();
    out.mean_m += e / double(from.size());
    out.max_m = std::max(out.max_m, e);
  }
  out.rmse_m = alignment.rmse_m;
  return out;
}

}  // namespace slamkit

namespace slamkit {

ReferenceComparison CompareWithReference(const Trajectory& estimate, const Trajectory& reference,
                                         int step) {
  if (estimate.size() != reference.size() || step < 1) {
    throw std::invalid_argument(fmt::format(
        "CompareWithReference: {} estimated poses for {} reference poses (step {})",
        estimate.size(), reference.size(), step));
  }
  // Re-stamp both with the pose index so that pairing cannot depend on the log's clock.
  Trajectory est = estimate, ref = reference;
  for (std::size_t i = 0; i < est.size(); ++i) est[i].t_s = ref[i].t_s = double(i);
  std::vector<PoseRelation> relations;
  for (std::size_t i = 0; i + step < ref.size(); ++i) {
    relations.push_back({double(i), double(i + step), ref[i].pose.Between(ref[i + step].pose)});
  }
  return {AbsoluteTrajectoryError(est, ref, 0.25), EvaluateRelations(est, relations, 0.25)};
}

}  // namespace slamkit
