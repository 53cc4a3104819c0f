#pragma once

#include <deque>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/planning/kmeans.hpp"

namespace slamkit {

struct SwslamPlannerParams {
  // N: an area of interest is detected when the landmark counts of the last N observation
  // periods rise strictly (seed 001 Sec. 4: "increasing monotonously within three observation
  // periods"). ≥ 2.
  int trigger_periods = 3;
  // The clustering of the area's landmarks (k = 3: seed 001 does not give k; three leaves room
  // for the dense cluster, the sparse background and a neighbouring cluster's edge).
  KMeansParams kmeans;
  // false: detect the areas of interest and delimit the route sections, but never detour (the
  // route run, so that its sections can be set beside SWSLAM's).
  bool detour = true;
  // A detour not reached within this many observation periods is abandoned: a car-like vehicle
  // sent to a point inside its turning circle can circle it for ever. ≥ 1.
  int max_detour_periods = 60;
  // An area is of interest only if its largest cluster holds at least this many landmarks, and
  // only if that cluster's centre is farther than `revisit_radius_m` from every earlier detour:
  // the counts also rise at the edge of a sparse background or when the route passes a cluster
  // it has already mapped, and the seed's areas of interest are the dense clusters, each visited
  // once. Otherwise no section opens and the trigger starts a fresh window. The defaults keep
  // every detection (1, 0).
  int min_cluster_landmarks = 1;
  double revisit_radius_m = 0.0;
};

// The area-of-interest test of SPEC S2 (seed 001 Sec. 3.2, Step 3). What counts in a period is
// the number of distinct landmarks of the filter's map that the period's scan was associated
// with (matched or newly mapped; dropped sightings name no landmark and do not count). It fires
// at a period when the counts of the last N periods, that one included, rise strictly:
// n[p-N+1] < … < n[p-1] < n[p] (N - 1 rises over N periods).
class AreaOfInterestTrigger {
 public:
  explicit AreaOfInterestTrigger(int periods = 3);

  // Adds one period's landmarks (indices into the filter's map); returns whether it fires.
  bool Add(std::vector<int> landmarks);
  // The distinct landmarks of the last N periods, ascending: the area's landmarks.
  std::vector<int> AreaLandmarks() const;
  // Forgets the periods seen so far: a new run of N periods is needed to fire.
  void Clear() { window_.clear(); }

 private:
  int periods_;
  std::deque<std::vector<int>> window_;  // the last N periods' distinct landmarks, oldest first
};

// Where the vehicle's controller is on its route, as the planner is told after each period.
struct RouteProgress {
  int route_waypoint = 0;  // the route waypoint it heads for (or resumes at after a detour)
  bool on_detour = false;  // still driving to the detour it was given (false once reached)
};

// A route section as seed 001 Sec. 4.1 defines it: "the route of the robot from the observed
// area of interest to the next step waypoint". It starts at the period that detected the area
// and ends when the route waypoint the vehicle was heading for is reached (after the detour, if
// any), so a run without detours has the same sections for comparison.
struct RouteSection {
  int first_period = 0;    // the period that detected the area (periods count from 0)
  int end_period = -1;     // the first period after it; -1: open until the end of the run
  int route_waypoint = 0;  // the route waypoint whose reaching ends it
  std::optional<Eigen::Vector2d> detour_m;  // the self-detected waypoint (none without detours)
  bool detour_reached = false;  // false: none, or abandoned after max_detour_periods
};

// SWSLAM's waypoint selection (SPEC S2; seed 001 Secs. 3.1-3.2). Each observation period it
// counts the landmarks the scan was associated with; when the area-of-interest trigger fires it
// clusters the filter's estimates of the area's landmarks by K-means and sends the vehicle to
// the centre of the largest cluster, after which the route resumes at its current waypoint.
// Cooldown: after a detection, no new one until the section ends (the route waypoint is
// reached). While the vehicle drives into a dense cluster the counts keep rising, so without it
// the trigger would re-cluster every period and chase its own target; and the seed's Fig. 1 and
// Sec. 4.1 have one self-detected waypoint per route section. The trigger's window is cleared
// when the section ends, so the next detection needs N fresh periods.
// The planner sees only the filter (its map, only when the trigger fires) and the filter's
// association decisions, never the truth.
class SwslamPlanner {
 public:
  // `rng` (K-means++ seeding) must outlive the planner.
  SwslamPlanner(const SwslamPlannerParams& params, Rng& rng);

  // One observation period, after the filter's update with that scan's `decisions`. Returns the
  // detour the controller should drive to now; nullopt: follow the route.
  std::optional<Eigen::Vector2d> OnPeriod(std::span<const AssociationDecision> decisions,
                                          const LandmarkSlamFilter& filter,
                                          const RouteProgress& progress);

  const std::vector<RouteSection>& Sections() const { return sections_; }
  // The centres of the clusters chosen as detours, in order.
  const std::vector<Eigen::Vector2d>& ChosenCentres() const { return centres_m_; }
  int Periods() const { return periods_; }

 private:
  enum class State { kWatching, kDetour, kCooldown };

  void DetectArea(int period, const LandmarkSlamFilter& filter, const RouteProgress& progress);
  // The largest cluster's centre, or nullopt when the area is not of interest (see params).
  std::optional<Eigen::Vector2d> ChooseWaypoint(const LandmarkSlamFilter& filter);
  void FollowDetour(int period, const RouteProgress& progress);
  void EndSectionIfReached(int period, const RouteProgress& progress);

  SwslamPlannerParams params_;
  Rng& rng_;
  AreaOfInterestTrigger trigger_;
  State state_ = State::kWatching;
  int periods_ = 0;
  std::vector<RouteSection> sections_;
  std::vector<Eigen::Vector2d> centres_m_;
  std::vector<Eigen::Vector2d> considered_m_;  // every accepted area's centre, detour or not
};

// The distinct landmarks a scan's decisions name (matched or new), ascending.
std::vector<int> AssociatedLandmarks(std::span<const AssociationDecision> decisions);

}  // namespace slamkit
