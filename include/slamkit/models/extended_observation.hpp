#pragma once

#include <Eigen/Core>

#include "slamkit/models/range_bearing.hpp"

namespace slamkit {

// SPEC S3: a vehicle–vehicle ("v-v") sighting is vehicle b's position as range and bearing from
// vehicle a's pose, the range-bearing model with b's position as the landmark. J_out_b is with
// respect to b's whole pose (its heading column is zero).
RangeBearing PredictVehicleSighting(const Pose2& a, const Pose2& b,
                                    Eigen::Matrix<double, 2, 3>* J_out_a = nullptr,
                                    Eigen::Matrix<double, 2, 3>* J_out_b = nullptr);

// The inputs of an extended observation, in the order of its Jacobian's columns: a's v-v
// sighting of b (range, bearing), b's sighting of a feature (range, bearing) and b's heading
// relative to a's (φ_b − φ_a).
using ExtendedObservationJacobian = Eigen::Matrix<double, 2, 5>;

// SPEC S3, seed 002 Eqs. 8-14: the feature that b sights at z_bf, as range and bearing from a,
// through a's v-v sighting z_ab of b: t_af = t_ab + R(Δφ) t_bf, with t_ab and t_bf the two
// sightings' points in a's and b's frames and Δφ b's heading relative to a's. J_out_in is
// ∂(r, β)/∂(r_ab, β_ab, r_bf, β_bf, Δφ).
RangeBearing ComposeExtendedObservation(const RangeBearing& z_ab, const RangeBearing& z_bf,
                                        double relative_heading_rad,
                                        ExtendedObservationJacobian* J_out_in = nullptr);

// R^e, the covariance of the extended observation: J diag(R_ab, R_bf, var Δφ) Jᵀ, the inputs
// taken as independent (the seed's assumption: SPEC S3, and docs/cooperative.md for what it
// costs when one v-v sighting extends many).
Eigen::Matrix2d ExtendedObservationCovariance(const ExtendedObservationJacobian& J,
                                              const Eigen::Matrix2d& R_ab,
                                              const Eigen::Matrix2d& R_bf,
                                              double relative_heading_variance_rad2);

}  // namespace slamkit
