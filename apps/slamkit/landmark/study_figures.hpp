#pragma once

// The figures of `slamkit study`: the runners' results as the report module's figure data.

#include <filesystem>

#include "slamkit/report/figures.hpp"
#include "slamkit/runners/landmark/study.hpp"

namespace slamkit::app {

// DIR/nees.png: each method's mean pose NEES per step over its runs still running (seed 001's
// Fig. 3: EKF-SLAM blue, FastSLAM green, SWSLAM red) with the 95 % χ² band of a mean over all
// the runs; DIR/path.png: SWSLAM's run 0, its true and estimated paths, the true landmarks, its
// map and the cluster centres it chose as waypoints.
void WriteStudyFigures(const std::filesystem::path& dir, const std::string& scenario,
                       const StudyResult& result);

}  // namespace slamkit::app
