#include "slamkit/features/scan_features.hpp"

namespace slamkit {

// SPEC S1, feature extraction.
ScanFeatures ExtractFeatures(const LaserScan& scan, const LineExtractionParams& params) {
  ScanFeatures f;
  f.lines = ExtractLines(scan, params);
  f.corners = ExtractCorners(f.lines, params);
  return f;
}

ScanFeatures ToRobotFrame(const ScanFeatures& sensor_frame, const Pose2& laser_offset) {
  ScanFeatures f = sensor_frame;
  for (LineSegment& s : f.lines) {
    Eigen::Matrix2d J;
    s.line = InvertLine(laser_offset, s.line, nullptr, &J);
    s.covariance = J * s.covariance * J.transpose();
    s.start_m = laser_offset.TransformFrom(s.start_m);
    s.end_m = laser_offset.TransformFrom(s.end_m);
  }
  for (Corner& c : f.corners) {
    Eigen::Matrix2d J;
    c.point_m = laser_offset.TransformFrom(c.point_m, nullptr, &J);
    c.covariance = J * c.covariance * J.transpose();
  }
  return f;
}

}  // namespace slamkit
