#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// Frontiers on an occupancy grid (SPEC S4, step 1: the target frontier cell f lies between
// explored and unexplored space; Yamauchi 1997).
struct GridFrontierParams {
  // A known cell below this occupancy is free: a robot may stand there.
  double free_probability = 0.35;
  // A known cell above this occupancy is occupied. A cell between the two is unexplored, as an
  // unknown one: a cell one beam has crossed (log-odds −0.4, p = 0.40) is neither free nor a wall,
  // and a free cell beside it is where exploring goes on (at the laser's range, where the beams
  // spread wider than a cell, such cells close corridors off otherwise).
  double occupied_probability = 0.65;
  // Regions of fewer frontier cells are dropped: a single unknown cell among free ones is a
  // beam that missed it, not a way into new space.
  int min_region_cells = 5;
};

// Whether `c` is a frontier cell: free, with a 4-neighbour neither free nor occupied (unknown, or
// between the two thresholds).
bool IsFrontierCell(const OccupancyGrid& grid, const CellIndex& c, const GridFrontierParams& params);

// Whether `c` is a frontier cell of a region FindFrontierRegions keeps (min_region_cells or more):
// the region is grown from `c` only until it is large enough, so a search that meets frontier
// cells one at a time need not list every frontier of the map first.
bool InFrontierRegion(const OccupancyGrid& grid, const CellIndex& c,
                      const GridFrontierParams& params = {});

// One 8-connected group of frontier cells.
struct FrontierRegion {
  std::vector<CellIndex> cells;  // in the order the search reached them
  Eigen::Vector2d centroid_m = Eigen::Vector2d::Zero();  // the mean of the cells' centres
};

// The frontier cells of `grid`: free cells with an unknown 4-neighbour, searched over the cells
// written so far (an unknown border beyond them counts), grouped into 8-connected regions of at
// least min_region_cells, largest first (ties: the first found first).
std::vector<FrontierRegion> FindFrontierRegions(const OccupancyGrid& grid,
                                                const GridFrontierParams& params = {});

}  // namespace slamkit
