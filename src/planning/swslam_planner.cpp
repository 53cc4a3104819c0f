#include "slamkit/planning/swslam_planner.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace slamkit {

AreaOfInterestTrigger::AreaOfInterestTrigger(int periods) : periods_(periods) {
  if (periods < 2) throw std::invalid_argument("AreaOfInterestTrigger: periods must be >= 2");
}

// SPEC S2, seed 001 Sec. 3.2, Step 3: the counts of N consecutive periods rise strictly.
bool AreaOfInterestTrigger::Add(std::vector<int> landmarks) {
  window_.push_back(std::move(landmarks));
  if (static_cast<int>(window_.size()) > periods_) window_.pop_front();
  if (static_cast<int>(window_.size()) < periods_) return false;
  for (std::size_t i = 1; i < window_.size(); ++i) {
    if (window_[i].size() <= window_[i - 1].size()) return false;
  }
  return true;
}

std::vector<int> AreaOfInterestTrigger::AreaLandmarks() const {
  std::vector<int> all;
  for (const std::vector<int>& period : window_) all.insert(all.end(), period.begin(), period.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

std::vector<int> AssociatedLandmarks(std::span<const AssociationDecision> decisions) {
  std::vector<int> seen;
  for (const AssociationDecision& d : decisions) {
    if (d.kind != AssociationDecision::Kind::kDropped && d.landmark >= 0) {
      seen.push_back(d.landmark);
    }
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  return seen;
}

SwslamPlanner::SwslamPlanner(const SwslamPlannerParams& params, Rng& rng)
    : params_(params), rng_(rng), trigger_(params.trigger_periods) {
  if (params.max_detour_periods < 1) {
    throw std::invalid_argument("SwslamPlanner: max_detour_periods must be >= 1");
  }
}

std::optional<Eigen::Vector2d> SwslamPlanner::OnPeriod(
    std::span<const AssociationDecision> decisions, const LandmarkSlamFilter& filter,
    const RouteProgress& progress) {
  const int period = periods_++;
  if (state_ == State::kDetour) FollowDetour(period, progress);
  if (state_ == State::kCooldown) EndSectionIfReached(period, progress);
  if (state_ == State::kWatching && trigger_.Add(AssociatedLandmarks(decisions))) {
    DetectArea(period, filter, progress);
  }
  if (state_ != State::kDetour) return std::nullopt;
  return sections_.back().detour_m;
}

// Seed 001 Sec. 3.2, Step 3: an area of interest opens a route section (Sec. 4.1) and, with
// detours, picks its waypoint (Sec. 3.1).
void SwslamPlanner::DetectArea(int period, const LandmarkSlamFilter& filter,
                               const RouteProgress& progress) {
  RouteSection section;
  section.first_period = period;
  section.route_waypoint = progress.route_waypoint;
  const std::optional<Eigen::Vector2d> waypoint = ChooseWaypoint(filter);
  if (!waypoint) {
    trigger_.Clear();
    return;
  }
  if (params_.detour) {
    section.detour_m = waypoint;
    centres_m_.push_back(*waypoint);
  }
  sections_.push_back(section);
  state_ = params_.detour ? State::kDetour : State::kCooldown;
}

// Seed 001 Sec. 3.1, Steps 1-5: K-means on the filter's estimates of the landmarks seen in the
// triggering periods; the centre of the cluster with the most landmarks is the next waypoint.
std::optional<Eigen::Vector2d> SwslamPlanner::ChooseWaypoint(const LandmarkSlamFilter& filter) {
  const LandmarkMap map = filter.Map();
  std::vector<Eigen::Vector2d> points;
  for (int i : trigger_.AreaLandmarks()) {
    if (i < static_cast<int>(map.landmarks.size())) points.push_back(map.landmarks[i].position_m);
  }
  // The trigger fired on rising counts, so the last period named at least one landmark.
  const KMeansResult clusters = KMeans(points, params_.kmeans, rng_);
  const int largest = LargestCluster(clusters);
  const Eigen::Vector2d centre = clusters.centres_m[largest];
  if (clusters.sizes[largest] < params_.min_cluster_landmarks) return std::nullopt;
  for (const Eigen::Vector2d& earlier : considered_m_) {
    if ((earlier - centre).norm() < params_.revisit_radius_m) return std::nullopt;
  }
  considered_m_.push_back(centre);
  return centre;
}

void SwslamPlanner::FollowDetour(int period, const RouteProgress& progress) {
  RouteSection& section = sections_.back();
  if (!progress.on_detour) {
    section.detour_reached = true;
    state_ = State::kCooldown;
  } else if (period - section.first_period >= params_.max_detour_periods) {
    state_ = State::kCooldown;  // abandoned: OnPeriod now returns nullopt, the route resumes
  }
}

void SwslamPlanner::EndSectionIfReached(int period, const RouteProgress& progress) {
  if (progress.route_waypoint == sections_.back().route_waypoint) return;
  sections_.back().end_period = period;
  trigger_.Clear();
  state_ = State::kWatching;
}

}  // namespace slamkit
