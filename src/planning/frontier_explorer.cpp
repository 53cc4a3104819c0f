#include "slamkit/planning/frontier_explorer.hpp"

#include <algorithm>
#include <cmath>

namespace slamkit {

FrontierExplorer::FrontierExplorer(const FrontierExplorerParams& params)
    : params_(params), escape_(params.avoidance) {}

// SPEC S1, active loop: reach a frontier, choose the next; with none in sight turn in place; an
// obstacle on the way is passed tangentially without giving up the goal.
Control FrontierExplorer::Step(const Pose2& estimate, const LaserScan& scan, double t_s) {
  if (visited_.empty()) {  // the start is explored
    visited_.push_back(estimate.translation());
    path_.push_back(estimate.translation());
  }
  Control u = Control::Zero(2);
  if (mode_ != ExplorerMode::kDone) {
    FinishGoalIfDone(estimate, t_s);
    if (mode_ != ExplorerMode::kReturning &&
        (estimate.translation() - path_.back()).norm() >= params_.breadcrumb_spacing_m) {
      path_.push_back(estimate.translation());
    }
    const std::vector<Frontier> frontiers = FindFrontiers(scan, estimate, params_.frontiers);
    if (!goal_) ChooseGoal(estimate, frontiers, t_s);
    KeepForLater(frontiers);
    u = goal_ ? Drive(estimate, scan, t_s) : TurnInPlace(estimate, t_s);
  }
  last_t_s_ = t_s;
  return u;
}

// A goal reached or timed out is visited; on the way back to a pending frontier the next leg
// starts (those points were visited already).
void FrontierExplorer::FinishGoalIfDone(const Pose2& estimate, double t_s) {
  if (!goal_) return;
  const bool reached = (*goal_ - estimate.translation()).norm() < params_.reach_radius_m;
  if (!reached && t_s - goal_started_s_ < params_.goal_timeout_s) return;
  // Where the robot is, not the goal. A point on the way back was visited already.
  if (route_.empty()) visited_.push_back(estimate.translation());
  goal_.reset();
  if (!route_.empty()) {
    const Eigen::Vector2d next = route_.back();
    route_.pop_back();
    SetGoal(next, estimate, t_s);
    if (!route_.empty()) mode_ = ExplorerMode::kReturning;
  }
}

// The frontier the robot turns least to face becomes the goal.
void FrontierExplorer::ChooseGoal(const Pose2& estimate, const std::vector<Frontier>& frontiers,
                                  double t_s) {
  const std::optional<Frontier> next = ChooseFrontier(frontiers, visited_, params_.choice);
  if (next) SetGoal(next->point_world_m, estimate, t_s);
}

// Frontiers in sight that are not yet known (pending, visited or the goal, within the revisit
// radius), for when the branch the robot follows runs out.
void FrontierExplorer::KeepForLater(const std::vector<Frontier>& frontiers) {
  const double r = params_.choice.revisit_radius_m;
  const auto near = [r](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - b).norm() < r;
  };
  for (const Frontier& f : frontiers) {
    const Eigen::Vector2d& p = f.point_world_m;
    if (goal_ && near(p, *goal_)) continue;
    if (std::any_of(visited_.begin(), visited_.end(), [&](const auto& v) { return near(p, v); }) ||
        std::any_of(pending_.begin(), pending_.end(), [&](const Pending& q) {
          return near(p, q.point_m);
        })) {
      continue;
    }
    pending_.push_back({p, path_.size()});
  }
}

void FrontierExplorer::SetGoal(const Eigen::Vector2d& goal, const Pose2& estimate, double t_s) {
  goal_ = goal;
  trajectory_ = {.start_m = estimate.translation(), .goal_m = goal,
                 .speed_mps = params_.control.speed_mps, .t0_s = t_s};
  goal_started_s_ = t_s;
  escape_.Reset();
  escaping_ = false;
  turned_rad_ = 0.0;
  mode_ = ExplorerMode::kTracking;
}

// The latest pending frontier that no visited point has covered since: back along the path to
// where it was seen (popping the path), then the frontier itself.
bool FrontierExplorer::ReturnToPending(const Pose2& estimate, double t_s) {
  const auto covered = [&](const Pending& p) {
    return std::any_of(visited_.begin(), visited_.end(), [&](const Eigen::Vector2d& v) {
      return (p.point_m - v).norm() < params_.choice.revisit_radius_m;
    });
  };
  while (!pending_.empty() && covered(pending_.back())) pending_.pop_back();
  if (pending_.empty()) return false;
  const Pending target = pending_.back();
  pending_.pop_back();
  route_ = {target.point_m};
  // It was seen near path_[depth - 1]; path_.back() is where the robot is.
  for (std::size_t i = target.depth - 1; i + 1 < path_.size(); ++i) route_.push_back(path_[i]);
  path_.resize(target.depth);
  const Eigen::Vector2d first = route_.back();
  route_.pop_back();
  SetGoal(first, estimate, t_s);
  if (!route_.empty()) mode_ = ExplorerMode::kReturning;
  return true;
}

// One full turn without a frontier: back to a pending one, or the end of the exploration.
Control FrontierExplorer::TurnInPlace(const Pose2& estimate, double t_s) {
  if (last_t_s_ && mode_ == ExplorerMode::kTurning) {
    turned_rad_ += std::abs(params_.turn_rate_radps) * (t_s - *last_t_s_);
  }
  mode_ = ExplorerMode::kTurning;
  if (turned_rad_ >= 2.0 * M_PI) {
    if (ReturnToPending(estimate, t_s)) return Drive(estimate, LaserScan{}, t_s);
    mode_ = ExplorerMode::kDone;
    return Control::Zero(2);
  }
  Control u = Control::Zero(2);
  u(1) = params_.turn_rate_radps;
  return u;
}

// Tracking the straight trajectory, or escaping an obstacle toward a point as far off as the
// goal; after an escape the straight trajectory starts again from where the robot is.
Control FrontierExplorer::Drive(const Pose2& estimate, const LaserScan& scan, double t_s) {
  const std::optional<Eigen::Vector2d> escape = escape_.Direction(estimate, *goal_, scan);
  if (escape) {
    escaping_ = true;
    if (mode_ == ExplorerMode::kTracking) mode_ = ExplorerMode::kAvoiding;
    const double distance = (*goal_ - estimate.translation()).norm();
    return TrackReference(estimate, estimate.translation() + distance * *escape,
                          Eigen::Vector2d::Zero(), params_.control);
  }
  if (escaping_) {
    trajectory_ = {.start_m = estimate.translation(), .goal_m = *goal_,
                   .speed_mps = params_.control.speed_mps, .t0_s = t_s};
    escaping_ = false;
    if (mode_ == ExplorerMode::kAvoiding) mode_ = ExplorerMode::kTracking;
  }
  return TrackReference(estimate, trajectory_.Position(t_s), trajectory_.Velocity(t_s),
                        params_.control);
}

}  // namespace slamkit
