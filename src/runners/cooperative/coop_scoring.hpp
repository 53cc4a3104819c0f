// Scoring one vehicle's trace of a cooperative run against the fleet's truth (coop_run.cpp).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/runners/cooperative/coop_run.hpp"

namespace slamkit::internal {

// The true pose at t: the nearer sample around it, if one is within 0.5 s (a recording whose
// truth stops early, or has a hole, is scored where it has truth only).
std::optional<Pose2> TruthAt(const Trajectory& path, double t);

// Records the estimate at t when the truth has a pose then; returns whether it did.
bool Record(CoopVehicleTrace& trace, double t, const Pose2& estimate, const Eigen::Matrix3d& cov,
            const Trajectory& truth);

// Fills the trace's errors, NEES, RMSE and (landmark index -> true id) map error.
void Summarise(CoopVehicleTrace& trace, const LandmarkWorld& world,
               const std::vector<LandmarkId>& landmark_truth);

// Each vehicle's controls integrated from its start pose.
CoopModeResult DeadReckoning(const FleetLog& log, const FleetTruth& truth,
                             const CoopFilterParams& p);

}  // namespace slamkit::internal
