#pragma once

#include "slamkit/core/pose2.hpp"
#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

// How far AlignMaps searches (`slamkit mapdiff --align`): two runs of one log start in frames
// that differ by the filters' errors at the start, a few cells and degrees, not metres.
struct MapAlignmentParams {
  double max_shift_m = 2.0;           // |dx|, |dy| searched
  double max_rotation_rad = 0.1745;   // |θ| searched (10°)
  double occupied_threshold = 0.65;   // a pixel above this occupancy is a wall (map_server's)
  int max_points = 4000;              // the second map's wall cells used, evenly subsampled
};

struct MapAlignment {
  Pose2 transform;        // takes a point of the second map's frame into the first's
  // The second map's wall cells on a wall of the first count 1, beside one 1/2, over them all.
  double score = 0.0;
};

// The rigid motion that lays the second map's walls best onto the first's: an exhaustive search
// over the rotations and shifts within the bounds in steps of 4 cells (and 4 cells' turn at the
// walls' extent), then around the best in steps of one cell, then of a quarter. Throws
// std::invalid_argument for other resolutions or negative bounds. Deterministic.
MapAlignment AlignMaps(const OccupancyImage& first, const OccupancyImage& second,
                       const MapAlignmentParams& params = {});

// The second map resampled into the first's pixel grid through `transform` (nearest pixel;
// pixels of the first's grid that fall outside the second map are unknown, 205).
OccupancyImage ResampleMap(const OccupancyImage& first, const OccupancyImage& second,
                           const Pose2& transform);

}  // namespace slamkit
