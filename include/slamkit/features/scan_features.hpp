#pragma once

#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/features/corners.hpp"
#include "slamkit/features/line_extraction.hpp"

namespace slamkit {

// The lines and corners of one scan, in the sensor frame (the scan's laser_offset is not applied:
// InvertLine(laser_offset, line) and laser_offset.TransformFrom(point) bring them to the robot).
struct ScanFeatures {
  std::vector<LineSegment> lines;  // beam order
  std::vector<Corner> corners;     // first_line / second_line index `lines`
};

// SPEC S1, feature extraction: ExtractLines, then ExtractCorners on its result.
ScanFeatures ExtractFeatures(const LaserScan& scan, const LineExtractionParams& params = {});

}  // namespace slamkit
