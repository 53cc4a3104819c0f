#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// Which directions of the pose a scan match pins down. In a corridor whose ends are out of
// reach every wall is parallel to it, so the score cannot tell where along it the robot is; the
// climb then follows whatever breaks the tie, mostly the unmapped part ahead, where fewer beams
// find a wall, and drags the robot back toward the mapped part scan after scan (Zhang, Kaess and
// Singh 2016 call this degeneracy; their "solution remapping" keeps the prior in the
// unconstrained directions, as MatchScan does with this analysis).
struct MatchConstraintParams {
  // A direction of the pose is unconstrained when its information is below this fraction of the
  // best-constrained direction's. Zero switches the analysis off.
  double min_information_ratio = 0.005;
  // The normal of a beam end is fitted to the ends of the beams within this many indices of it
  // that lie within normal_radius_m; it counts only if the fit is a line (the smaller spread
  // below max_normal_spread of the larger).
  int normal_neighbours = 5;
  double normal_radius_m = 0.5;
  double max_normal_spread = 0.1;
};

// The unit normal of the surface at each point of `ends` (consecutive beam ends of one scan, in
// beam order), or zero where the neighbours do not form a line (a corner, an isolated return).
std::vector<Eigen::Vector2d> EstimateNormals(const std::vector<Eigen::Vector2d>& ends,
                                             const MatchConstraintParams& params);

// The information the matched beams give about the pose (x, y, ℓθ), ℓ the RMS distance of the
// ends from the robot (so a turn and a shift that move the ends alike weigh alike): Σ JᵀJ over
// the beams with hit[i] != 0 and a normal, J = [nᵀ, n × p / ℓ] the derivative of the end's
// distance to its wall along the normal n (robot frame; the information of a translation is
// independent of the heading). `ends`, `normals` and `hit` are parallel.
struct MatchInformation {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  double length_m = 1.0;  // ℓ
};
MatchInformation ComputeMatchInformation(const std::vector<Eigen::Vector2d>& ends,
                                         const std::vector<Eigen::Vector2d>& normals,
                                         const std::vector<std::uint8_t>& hit);

// What a match says about each direction of the pose: `keep` maps a move (dx, dy, dθ) in the
// robot frame to its constrained part (the identity for a well-constrained match; it removes the
// directions whose information is below params.min_information_ratio of the largest one's).
struct MatchConstraints {
  Eigen::Matrix3d keep = Eigen::Matrix3d::Identity();
  int unconstrained = 0;  // how many directions it removes
  // `keep` for a move in the world frame (dx, dy, dθ) of a robot heading `theta_rad`.
  Eigen::Matrix3d KeepInWorld(double theta_rad) const;
};
MatchConstraints FindConstraints(const MatchInformation& info, const MatchConstraintParams& params);

// `match` with the part of its move away from `initial` that `constraints` removes taken back:
// the pose keeps the initial guess where the scan says nothing and the match everywhere else.
Pose2 KeepGuessAlong(const Pose2& initial, const Pose2& match, const MatchConstraints& constraints);

}  // namespace slamkit
