#include "slamkit/eval/trajectory_errors.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
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

std::optional<Pose2> InterpolatePoseAt(const Trajectory& trajectory, double t_s,
                                       double time_tolerance_s) {
  const int nearest = FindPoseAt(trajectory, t_s, time_tolerance_s);
  if (nearest >= 0) return trajectory[static_cast<std::size_t>(nearest)].pose;
  const auto after = std::lower_bound(trajectory.begin(), trajectory.end(), t_s,
                                      [](const StampedPose& p, double t) { return p.t_s < t; });
  if (after == trajectory.begin() || after == trajectory.end()) return std::nullopt;
  const StampedPose& a = *std::prev(after);
  const StampedPose& b = *after;
  const double s = (t_s - a.t_s) / (b.t_s - a.t_s);  // b.t_s > t_s > a.t_s: no division by 0
  const Eigen::Vector2d p =
      a.pose.translation() + s * (b.pose.translation() - a.pose.translation());
  const double heading = a.pose.theta() + s * WrapAngle(b.pose.theta() - a.pose.theta());
  return Pose2(p.x(), p.y(), WrapAngle(heading));
}

// Kümmerle et al. 2009, Eq. 2 with the translational and rotational parts kept apart.
RelationErrorStats EvaluateRelations(const Trajectory& unsorted_estimate,
                                     std::span<const PoseRelation> relations,
                                     double time_tolerance_s) {
  const Trajectory estimate = SortedByTime(unsorted_estimate);
  std::vector<double> trans, rot;
  trans.reserve(relations.size());
  rot.reserve(relations.size());
  int skipped = 0;
  for (const PoseRelation& r : relations) {
    const std::optional<Pose2> x1 = InterpolatePoseAt(estimate, r.t1_s, time_tolerance_s);
    const std::optional<Pose2> x2 = InterpolatePoseAt(estimate, r.t2_s, time_tolerance_s);
    if (!x1 || !x2) {
      ++skipped;
      continue;
    }
    const Pose2 error = r.delta.Between(x1->Between(*x2));
    trans.push_back(error.translation().norm());
    rot.push_back(RadToDeg(std::abs(error.theta())));
  }
  if (trans.empty() && !relations.empty()) {
    // A mean of nothing would read as a perfect 0 m: most likely the relations of another log.
    const auto [first, last] = std::minmax_element(
        relations.begin(), relations.end(),
        [](const PoseRelation& a, const PoseRelation& b) { return a.t1_s < b.t1_s; });
    throw std::invalid_argument(fmt::format(
        "none of the {} relations lies within the trajectory's time span ({:.3f} to {:.3f} s; "
        "the relations start from {:.3f} to {:.3f} s): are they this log's?",
        relations.size(), estimate.empty() ? 0.0 : estimate.front().t_s,
        estimate.empty() ? 0.0 : estimate.back().t_s, first->t1_s, last->t1_s));
  }
  const MeanStd t = Summarise(trans), a = Summarise(rot);
  return {static_cast<int>(trans.size()), skipped, t.mean, t.std, a.mean, a.std};
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

namespace slamkit {

ReferenceComparison CompareWithReference(const Trajectory& estimate, const Trajectory& reference,
                                         PairBy pair_by, double time_tolerance_s) {
  if (pair_by == PairBy::kIndex) return CompareWithReference(estimate, reference);
  const Trajectory sorted = SortedByTime(estimate);
  Trajectory paired_estimate, paired_reference;
  for (const StampedPose& ref : reference) {
    const int i = FindPoseAt(sorted, ref.t_s, time_tolerance_s);
    if (i < 0) continue;
    paired_estimate.push_back(sorted[static_cast<std::size_t>(i)]);
    paired_reference.push_back(ref);
  }
  if (paired_reference.empty()) {
    throw std::invalid_argument(fmt::format(
        "no reference pose has an estimated pose within {} s (pair by index instead?)",
        time_tolerance_s));
  }
  return CompareWithReference(paired_estimate, paired_reference);
}

Trajectory WithIncreasingTimes(const Trajectory& trajectory, double min_step_s, int* moved) {
  Trajectory out = trajectory;
  int count = 0;
  for (std::size_t i = 1; i < out.size(); ++i) {
    const double earliest = out[i - 1].t_s + min_step_s;
    if (out[i].t_s < earliest) {
      out[i].t_s = earliest;
      ++count;
    }
  }
  if (moved != nullptr) *moved = count;
  return out;
}

std::string TimestampProblem(const Trajectory& trajectory, double time_tolerance_s) {
  int repeated = 0, backwards = 0;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    const double dt = trajectory[i].t_s - trajectory[i - 1].t_s;
    if (std::abs(dt) <= time_tolerance_s) {
      ++repeated;
    } else if (dt < 0.0) {
      ++backwards;
    }
  }
  if (repeated == 0 && backwards == 0) return "";
  return fmt::format("{} of {} timestamps repeat the previous one (within {} s) and {} go "
                     "backwards",
                     repeated, trajectory.size(), time_tolerance_s, backwards);
}

}  // namespace slamkit
