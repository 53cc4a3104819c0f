#pragma once

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// What a grid particle's proposal and scan likelihood read: its own map and, optionally, a second
// layer consulted only where the map is unknown (log-odds 0), such as P-SLAM's predicted structure
// (SPEC S4: the hypothesis h on unexplored cells). Both grids must have the same resolution (cell
// (0, 0) is at the origin in every grid). A plain map converts implicitly.
struct GridMapView {
  GridMapView(const OccupancyGrid& map_in,
              const OccupancyGrid* second_in = nullptr)  // NOLINT
      : map(map_in), second(second_in) {}

  // The cell as the view sees it, in the grids' kLogOddsStep units.
  OccupancyGrid::CellValue LogOddsSteps(const CellIndex& c) const {
    const OccupancyGrid::CellValue v = map.LogOddsSteps(c);
    return v != 0 || second == nullptr ? v : second->LogOddsSteps(c);
  }

  const OccupancyGrid& map;
  const OccupancyGrid* second;
};

}  // namespace slamkit
