#pragma once

#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/filters/ekf_slam.hpp"
#include "slamkit/io/isam_reader.hpp"
#include "slamkit/maps/landmark_map.hpp"

namespace slamkit {

struct IsamRunParams {
  EkfSlamParams ekf;
  // Multiplies every odometry covariance of the file (the file's are very small).
  double odometry_covariance_scale = 1.0;
  // Multiplies every sighting covariance of the file.
  double sighting_covariance_scale = 1.0;
};

// EKF-SLAM over an iSAM-format log (relative-point sightings, odometry with its own covariance).
struct IsamRunResult {
  Trajectory estimate;   // one pose per log pose, t = the pose's index in the file
  LandmarkMap map;
  int sightings = 0;
  int dropped = 0;
  // Share of sightings whose landmark is the one the file names, after matching our landmarks
  // one-to-one to the file's ids (greedily, by the number of sightings each pair shares).
  double association_agreement = 0.0;
  double wall_time_s = 0.0;
};

IsamRunResult RunEkfSlamOnIsam(const IsamLog& log, const IsamRunParams& params);

}  // namespace slamkit
