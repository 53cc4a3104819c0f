#pragma once

// The last centimetres of a localiser's pose: the scan matched against the saved map from the
// particle filter's estimate, as the grid filter tracks its scans between updates (the same
// matcher and gates). The particle filter stays what keeps the robot localised; this only
// sharpens the pose it reports.

#include <optional>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

struct MapScanRefinerParams {
  bool enabled = true;
  ScanMatcherParams matcher;         // the grid filter's tracking matcher (TrackingMatcherParams)
  double max_correction_m = 0.1;     // a match further than this from the estimate is not taken
  double max_correction_rad = 0.1;
  double usable_range_m = 50.0;
  // The match starts from the last refined pose moved by the odometry while that stays within
  // this of the particle filter's estimate (else from the estimate): the matched poses then
  // follow each other as the grid filter's tracking does, and the filter's estimate, which
  // drifts where the map does not explain the scans, only catches them when they go astray.
  double follow_gate_m = 1.0;
  // A scan this far (or turned this far) from the one before, as sparse logs give them, is
  // matched as the grid filter matches its particles at an update (coarse pass first) from the
  // estimate, and accepted within the far gates: the tracking matcher and its gates are meant
  // for the small steps between dense scans (the grid filter's tracking_max_step_*).
  ScanMatcherParams far_matcher;
  double far_step_m = 0.5;
  double far_step_rad = 0.25;
  double far_max_correction_m = 0.5;
  double far_max_correction_rad = 0.25;
};

// The defaults: the grid filter's tracking settings (RbpfGridSlamParams).
MapScanRefinerParams DefaultRefinerParams();

class MapScanRefiner {
 public:
  MapScanRefiner(OccupancyGrid map, const MapScanRefinerParams& params);

  // `estimate` moved to where `scan` matches the map, or `estimate` itself when the match is not
  // accepted or moves it beyond the gates; `refined` (optional) says which.
  Pose2 Refine(const LaserScan& scan, const Pose2& estimate, bool* refined = nullptr) const;
  // The same from `followed` (the last refined pose moved by the odometry since) when that lies
  // within follow_gate_m of `estimate`; as a far scan when the odometry `step` since the scan
  // before is far.
  Pose2 Refine(const LaserScan& scan, const Pose2& estimate, const std::optional<Pose2>& followed,
               const Pose2& step, bool* refined = nullptr) const;

 private:
  OccupancyGrid map_;
  Pose2 Match(const LaserScan& scan, const Pose2& start, const ScanMatcherParams& matcher,
              double max_correction_m, double max_correction_rad, bool* refined) const;

  MapScanRefinerParams params_;
};

}  // namespace slamkit
