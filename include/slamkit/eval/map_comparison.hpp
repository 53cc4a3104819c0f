#pragma once

#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

// How two map images are read and compared (SPEC S4: the Intel experiment's Eq. 24, and Eq. 5's
// similarity). A pixel v is the occupancy p = (255 − v) / 255, as map_server reads it; p above
// `occupied_threshold` is occupied, below `free_threshold` free, anything between unknown (the
// 205 of map_server's images, p = 0.196, is unknown with the defaults, as in map_server).
struct MapComparisonParams {
  double occupied_threshold = 0.65;  // map_server's occupied_thresh
  double free_threshold = 0.196;     // map_server's free_thresh
  // The KL divergence takes p in [floor, 1 − floor]: a cell at p = 0 or 1 in one map and not in
  // the other would otherwise make it infinite (a trinary image has only 0, 1 and unknown).
  double probability_floor = 1e-3;
  // Ψ counts an occupied cell as shared when the other map has one within this many cells (in
  // x and y): two maps of one wall, drawn from its two sides or rasterised from its line, put it
  // one cell apart as often as not. 0: Eq. 5 exactly.
  int dice_tolerance_cells = 0;
};

// Two maps over the cells they share (their overlap in the world; both at one resolution, their
// origins whole cells apart).
struct MapComparison {
  long cells = 0;        // cells of the overlap
  long known_cells = 0;  // of those, known (free or occupied) in at least one map
  // SPEC S4, Eq. 24: Σ over the known cells of the Bernoulli divergence
  // p log(p / q) + (1 − p) log((1 − p) / (1 − q)), p from the first map and q from the second;
  // an unknown cell counts as p = 0.5, the prior. 0 for a map against itself; not symmetric.
  double kl_divergence = 0.0;
  // The share of the known cells that are in the same class (free, occupied, unknown) in both.
  double cell_accuracy = 0.0;
  // SPEC S4, Eq. 5: Ψ = 2 |occ(A) ∩ occ(B)| / (|occ(A)| + |occ(B)|) over the overlap; 0 when
  // neither map has an occupied cell there. With a tolerance k: the occupied cells of either map
  // with an occupied cell of the other within k cells, over |occ(A)| + |occ(B)|.
  double dice_occupied = 0.0;
};

// Throws std::invalid_argument when the resolutions differ, the origins are not a whole number
// of cells apart, or the thresholds are not 0 ≤ free < occupied ≤ 1 and 0 < floor < 0.5.
MapComparison CompareMaps(const OccupancyImage& first, const OccupancyImage& second,
                          const MapComparisonParams& params = {});

}  // namespace slamkit
