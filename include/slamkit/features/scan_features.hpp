#pragma once

#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/features/corners.hpp"
#include "slamkit/features/line_extraction.hpp"

namespace slamkit {

// The lines and corners of one scan, in the sensor frame (the scan's laser_offset is not applied;
// ToRobotFrame does that).
struct ScanFeatures {
  std::vector<LineSegment> lines;  // beam order
  std::vector<Corner> corners;     // first_line / second_line index `lines`
};

// SPEC S1, feature extraction: ExtractLines, then ExtractCorners on its result.
ScanFeatures ExtractFeatures(const LaserScan& scan, const LineExtractionParams& params = {});

// The same features in the robot frame, given the laser's pose in it (LaserScan::laser_offset):
// lines through InvertLine, points through the offset, covariances through their Jacobians.
ScanFeatures ToRobotFrame(const ScanFeatures& sensor_frame, const Pose2& laser_offset);

}  // namespace slamkit
