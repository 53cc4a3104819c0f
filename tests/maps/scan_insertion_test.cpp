#include "slamkit/maps/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

// InsertScan: which cells a scan's beams mark free and occupied (SPEC S4's map update).
namespace slamkit {
namespace {

using Cells = std::vector<CellIndex>;

// Log-odds expected after the given free and hit cells have been updated, in update order.
std::map<std::pair<int, int>, float> ExpectedLogOdds(const Cells& free, const Cells& hits,
                                                     const OccupancyGridParams& p) {
  std::map<std::pair<int, int>, float> expected;
  for (const CellIndex& c : free) expected[{c.x, c.y}] += p.log_odds_miss;
  for (const CellIndex& c : hits) expected[{c.x, c.y}] += p.log_odds_hit;
  return expected;
}

void ExpectGridEquals(const OccupancyGrid& grid,
                      const std::map<std::pair<int, int>, float>& expected) {
  for (int y = -12; y <= 12; ++y) {
    for (int x = -12; x <= 12; ++x) {
      const auto it = expected.find({x, y});
      const float want = it == expected.end() ? 0.0f : it->second;
      // Cells hold log-odds in steps of 1/32: each update's change rounds by at most half a
      // step, and no cell here is updated more than 4 times.
      EXPECT_NEAR(grid.LogOdds({x, y}), want, 4.0 / 64.0) << "cell (" << x << ", " << y << ")";
    }
  }
}

LaserScan ThreeBeamScan(std::vector<float> ranges) {
  LaserScan scan;
  scan.angle_min_rad = -M_PI / 2.0;
  scan.angle_increment_rad = M_PI / 2.0;
  scan.max_range_m = 10.0;
  scan.ranges_m = std::move(ranges);
  return scan;
}

TEST(InsertScan, ThreeBeamsMarkExactlyTheirCells) {
  OccupancyGrid grid({.resolution_m = 1.0});
  InsertScan(grid, Pose2(0.5, 0.5, 0.0), ThreeBeamScan({3.0f, 4.0f, 2.0f}));
  // -y beam ends in (0,-3), +x beam in (4,0), +y beam in (0,2); the laser cell is free 3 times.
  const Cells free = {{0, 0}, {0, -1}, {0, -2}, {0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 0}, {0, 1}};
  const Cells hits = {{0, -3}, {4, 0}, {0, 2}};
  ExpectGridEquals(grid, ExpectedLogOdds(free, hits, grid.params()));
  EXPECT_EQ(grid.min_cell(), (CellIndex{0, -3}));
  EXPECT_EQ(grid.max_cell(), (CellIndex{4, 2}));
}

TEST(InsertScan, TheLaserHeadingRotatesTheBeams) {
  OccupancyGrid grid({.resolution_m = 0.5});
  // Heading +90°: the beams point +x, +y and -x; the laser is in cell (-3, 2).
  InsertScan(grid, Pose2(-1.25, 1.25, M_PI / 2.0), ThreeBeamScan({1.0f, 1.5f, 2.0f}));
  const Cells free = {{-3, 2}, {-2, 2}, {-3, 2}, {-3, 3}, {-3, 4}, {-3, 2}, {-4, 2}, {-5, 2},
                      {-6, 2}};
  const Cells hits = {{-1, 2}, {-3, 5}, {-7, 2}};
  ExpectGridEquals(grid, ExpectedLogOdds(free, hits, grid.params()));
}

TEST(InsertScan, NoReturnAndCutBeamsMarkFreeSpaceUpToTheUsableRangeOnly) {
  OccupancyGrid grid({.resolution_m = 1.0});
  LaserScan scan;
  scan.angle_min_rad = 0.0;
  scan.angle_increment_rad = M_PI / 2.0;
  scan.max_range_m = 10.0;
  // +x: no return (max range); +y: a return beyond the usable range of 3.2 m.
  scan.ranges_m = {10.0f, 5.0f};
  InsertScan(grid, Pose2(0.5, 0.5, 0.0), scan, {.usable_range_m = 3.2});
  // Both end at 3.7 m from the cell corner, in cells (3,0) and (0,3), which stay unknown.
  const Cells free = {{0, 0}, {1, 0}, {2, 0}, {0, 0}, {0, 1}, {0, 2}};
  ExpectGridEquals(grid, ExpectedLogOdds(free, {}, grid.params()));
}

TEST(InsertScan, NoReturnRaysStopAtTheirOwnLength) {
  LaserScan scan;
  scan.angle_min_rad = 0.0;
  scan.angle_increment_rad = M_PI / 2.0;
  scan.max_range_m = 10.0;
  scan.ranges_m = {10.0f, 5.0f};  // +x: no return; +y: a return beyond the usable range
  OccupancyGrid short_rays({.resolution_m = 1.0});
  InsertScan(short_rays, Pose2(0.5, 0.5, 0.0), scan,
             {.usable_range_m = 3.2, .no_return_ray_length_m = 1.2});
  // The no-return beam ends 1.7 m from the cell corner, in cell (1, 0); the cut return still
  // reaches cell (0, 3).
  ExpectGridEquals(short_rays,
                   ExpectedLogOdds({{0, 0}, {0, 0}, {0, 1}, {0, 2}}, {}, short_rays.params()));
  OccupancyGrid no_rays({.resolution_m = 1.0});
  InsertScan(no_rays, Pose2(0.5, 0.5, 0.0), scan,
             {.usable_range_m = 3.2, .no_return_ray_length_m = 0.0});
  ExpectGridEquals(no_rays, ExpectedLogOdds({{0, 0}, {0, 1}, {0, 2}}, {}, no_rays.params()));
}

TEST(InsertScan, InvalidRangesAreSkipped) {
  OccupancyGrid grid({.resolution_m = 1.0});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  InsertScan(grid, Pose2(0.5, 0.5, 0.0), ThreeBeamScan({nan, inf, 0.0f}));
  InsertScan(grid, Pose2(0.5, 0.5, 0.0), ThreeBeamScan({-1.0f, -inf, nan}));
  EXPECT_EQ(grid.TileCount(), 0u);
  EXPECT_GT(grid.min_cell().x, grid.max_cell().x);
}

// A wall seen at grazing angles: the far beams cross the wall's row of cells just before their
// own ends, through the cells their neighbours hit.
TEST(InsertScan, MissesSpareTheCellsTheSameScanHits) {
  const OccupancyGridParams params{.resolution_m = 0.05};
  const Pose2 laser(0.0125, 1.0125, 0.0);
  const double wall_y = 0.025;  // the middle of cell row 0
  LaserScan scan;
  scan.angle_min_rad = -1.5;
  scan.angle_increment_rad = 0.002;
  scan.max_range_m = 100.0;
  while (scan.BeamAngle(static_cast<int>(scan.ranges_m.size())) < -0.06) {
    const double a = scan.BeamAngle(static_cast<int>(scan.ranges_m.size()));
    scan.ranges_m.push_back(static_cast<float>((laser.y() - wall_y) / std::sin(-a)));
  }
  OccupancyGrid plain(params);
  OccupancyGrid spare(params);
  InsertScan(plain, laser, scan, {.usable_range_m = 100.0});
  InsertScan(spare, laser, scan, {.usable_range_m = 100.0, .misses_spare_scan_hits = true});
  std::map<std::pair<int, int>, bool> hit_cells;
  for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
    const double a = scan.BeamAngle(i);
    const CellIndex c = plain.WorldToCell(laser.translation() +
                                          double(scan.ranges_m[i]) * Eigen::Vector2d(std::cos(a),
                                                                                     std::sin(a)));
    hit_cells[{c.x, c.y}] = true;
  }
  int eroded_plain = 0;
  for (const auto& [xy, unused] : hit_cells) {
    const CellIndex c{xy.first, xy.second};
    EXPECT_GT(spare.LogOdds(c), 0.0f) << "hit cell (" << c.x << ", " << c.y << ")";
    if (plain.LogOdds(c) <= 0.0f) ++eroded_plain;
  }
  EXPECT_GE(eroded_plain, 5) << "without the option the scan erodes its own wall";
  // Elsewhere the two insertions agree cell for cell.
  for (int y = plain.min_cell().y; y <= plain.max_cell().y; ++y) {
    for (int x = plain.min_cell().x; x <= plain.max_cell().x; ++x) {
      if (hit_cells.count({x, y}) != 0) continue;
      ASSERT_EQ(plain.LogOdds({x, y}), spare.LogOdds({x, y})) << "cell (" << x << ", " << y << ")";
    }
  }
}

}  // namespace
}  // namespace slamkit
