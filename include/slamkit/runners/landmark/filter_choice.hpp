#pragma once

#include <string_view>

#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {

// The point-landmark filters the command line can name (--filter).
enum class FilterKind { kEkf, kFastSlam1, kFastSlam2 };

// "ekf", "fastslam1" or "fastslam2". Anything else is an InputError naming the value and the
// choices, so that a typo in a script fails with exit code 2.
FilterKind ParseFilterKind(std::string_view name);
std::string_view FilterName(FilterKind kind);
// "EKF-SLAM", "FastSLAM 1.0", "FastSLAM 2.0": for tables and legends.
std::string_view FilterTitle(FilterKind kind);

// FastSLAM set up as the EKF it is compared with: the proposal of `kind` (1.0: the motion,
// 2.0: the observation), `particles` particles, the EKF's association (known, or each
// particle's maximum likelihood), its new-landmark gate and its association margin. Throws
// std::invalid_argument for kEkf.
FastSlamParams FastSlamParamsFor(FilterKind kind, int particles, const EkfSlamParams& ekf);

// The filter `name` on the scenario's vehicle and sensor: the scenario's EKF, or FastSLAM as
// FastSlamParamsFor says, sampling as config.fastslam says (delayed sampling only with each
// particle's own association, as on logs). Throws InputError for an unknown name and for
// particles < 1.
LandmarkFilterFactory FactoryForFilter(std::string_view name, int particles,
                                       const ScenarioConfig& config);
LandmarkFilterFactory FactoryForFilter(FilterKind kind, int particles,
                                       const ScenarioConfig& config);

}  // namespace slamkit
