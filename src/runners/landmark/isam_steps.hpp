#pragma once

// What the iSAM runners give a filter and the smoother for each record of the log (private to
// src/runners): the run's noise, calibration and sighting model applied to the file's values.

#include <Eigen/Core>

#include "slamkit/io/isam_reader.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/point_sensor.hpp"
#include "slamkit/runners/landmark/isam_run.hpp"

namespace slamkit::isam_detail {

// The step's odometry covariance: the file's, scaled, plus the motion-proportional part.
Eigen::Matrix3d StepCovariance(const IsamStep& step, const IsamRunParams& params);
// The step's increment as the filter takes it: the file's, turned by the configured drift.
Control StepControl(const IsamStep& step, const IsamRunParams& params);
// The sighting's covariance: the range-bearing sensor's when configured, else the file's; scaled.
Eigen::Matrix2d SightingCovariance(const PointObservation& sighting, const IsamRunParams& params);

}  // namespace slamkit::isam_detail
