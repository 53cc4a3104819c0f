#include "slamkit/features/scan_features.hpp"

namespace slamkit {

// SPEC S1, feature extraction.
ScanFeatures ExtractFeatures(const LaserScan& scan, const LineExtractionParams& params) {
  ScanFeatures f;
  f.lines = ExtractLines(scan, params);
  f.corners = ExtractCorners(f.lines, params);
  return f;
}

}  // namespace slamkit
