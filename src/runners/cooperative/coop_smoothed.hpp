// The batch smoother of one vehicle's own data, the "mono-smoothed" mode (coop_run.cpp).
#pragma once

#include <vector>

#include "slamkit/core/fleet_log.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/runners/cooperative/coop_run.hpp"

namespace slamkit::internal {

struct MonoSmoothing {
  Trajectory path;                         // the smoothed pose at each node
  LandmarkMap map;                         // the smoothed landmarks (no covariance)
  std::vector<LandmarkId> landmark_truth;  // the map's true ids, in its order
  int sightings_used = 0;
  int sightings_dropped = 0;  // farther than params.known_gate_chi2 from the solution
};

// The batch maximum a posteriori of vehicle `vehicle`'s path and landmarks from what Mono uses:
// its start pose, its own controls (the filters' control noise) and its own landmark sightings
// with their true ids (`true_ids` parallel to log.events, or empty for the log's own ids),
// solved by eval's SmoothLandmarkSlam from `start` (the vehicle's filtered path; a node takes
// the latest pose there at or before its time). Nodes are at each sighting's time and at a
// control at least `node_period_s` after the node before; between nodes the held controls are
// composed with their noise as the filters predict. Sightings beyond known_gate_chi2 at a
// solution are dropped and the problem solved again (at most three times).
MonoSmoothing SmoothMonoVehicle(const FleetLog& log, const std::vector<LandmarkId>& true_ids,
                                int vehicle, const Trajectory& start,
                                const CoopFilterParams& params, double node_period_s = 0.25);

}  // namespace slamkit::internal
