#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// One step of an iSAM-format log: the odometry from the previous pose to this one (robot frame,
// with its covariance) and the landmarks sighted from the new pose (Cartesian, robot frame:
// x forward, y left; each with its covariance and the file's landmark id).
struct IsamStep {
  int pose_index = 0;
  Eigen::Vector3d odometry = Eigen::Vector3d::Zero();        // dx [m], dy [m], dθ [rad]
  Eigen::Matrix3d odometry_covariance = Eigen::Matrix3d::Zero();
  std::vector<PointObservation> sightings;
};

struct IsamLog {
  int initial_pose_index = 0;
  std::vector<PointObservation> initial_sightings;  // sightings from the first pose
  std::vector<IsamStep> steps;
};

// Reads `ODOMETRY i j dx dy dθ c_xx c_xy c_xθ c_yy c_yθ c_θθ` and `LANDMARK i l x y c_xx c_xy c_yy`
// lines (the Victoria Park file of ../shared/datasets). Odometry must chain (i = previous j);
// a landmark line refers to the latest pose. Throws InputError naming the file, line and field
// for an unknown record, a missing or non-numeric field, NaN/inf, a broken chain, or a covariance
// that is not positive definite. Bounds on what makes physical sense: every dx, dy, dθ, x, y has
// magnitude at most kIsamMaxMagnitude (metres or radians), every covariance entry at most
// kIsamMaxVariance (m², rad²); landmark ids are non-negative. A file without any record (empty,
// comments only) is an InputError, as is one in another format (unknown record, ROS bag).
inline constexpr double kIsamMaxMagnitude = 1e6;
inline constexpr double kIsamMaxVariance = 1e12;

IsamLog ReadIsamLog(const std::filesystem::path& path);

}  // namespace slamkit
