#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/features/grid_structure.hpp"
#include "common/grid_drawing.hpp"

namespace slamkit {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRes = 0.1;  // the grid of SPEC S4

OccupancyGrid MakeGrid() {
  OccupancyGridParams p;
  p.resolution_m = kRes;
  return OccupancyGrid(p);
}

using testing::DrawWall;

// A w × h room with its lower-left corner at `origin`, turned by `angle_rad` about it; its corners
// counter-clockwise from the origin.
std::array<Eigen::Vector2d, 4> DrawRoom(OccupancyGrid& grid, const Eigen::Vector2d& origin,
                                        double angle_rad, double w = 6.0, double h = 4.0) {
  const Eigen::Rotation2Dd R(angle_rad);
  const std::array<Eigen::Vector2d, 4> c = {origin, origin + R * Eigen::Vector2d(w, 0.0),
                                            origin + R * Eigen::Vector2d(w, h),
                                            origin + R * Eigen::Vector2d(0.0, h)};
  for (int i = 0; i < 4; ++i) DrawWall(grid, c[i], c[(i + 1) % 4]);
  return c;
}

Eigen::Vector2d Centre(const std::array<Eigen::Vector2d, 4>& c) {
  return 0.25 * (c[0] + c[1] + c[2] + c[3]);
}

double AngleDistance(double a, double b) { return std::abs(WrapAngle(a - b)); }

double Direction(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  const Eigen::Vector2d d = to - from;
  return std::atan2(d.y(), d.x());
}

// Each line's two ends lie within `tol` of two adjacent room corners, and its angle is the wall's.
void ExpectLinesAreTheWalls(const std::vector<GridLine>& lines,
                            const std::array<Eigen::Vector2d, 4>& c, double tol) {
  ASSERT_EQ(lines.size(), 4u);
  std::array<int, 4> found = {0, 0, 0, 0};
  for (const GridLine& l : lines) {
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector2d& a = c[i];
      const Eigen::Vector2d& b = c[(i + 1) % 4];
      const bool same = (l.start_m - a).norm() < tol && (l.end_m - b).norm() < tol;
      const bool reversed = (l.start_m - b).norm() < tol && (l.end_m - a).norm() < tol;
      if (!same && !reversed) continue;
      ++found[i];
      EXPECT_LT(AngleDistance(l.angle_rad, Direction(same ? a : b, same ? b : a)), 0.02);
      EXPECT_GT(l.angle_rad, -kPi / 2.0);
      EXPECT_LE(l.angle_rad, kPi / 2.0);
    }
  }
  for (int i = 0; i < 4; ++i) EXPECT_EQ(found[i], 1) << "wall " << i;
}

// One corner within `tol` of each room corner, its arms along the two walls that meet there.
void ExpectCornersAreTheRoomsCorners(const std::vector<GridCorner>& corners,
                                     const std::array<Eigen::Vector2d, 4>& c, double tol,
                                     double angle_tol) {
  ASSERT_EQ(corners.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const auto it = std::find_if(corners.begin(), corners.end(), [&](const GridCorner& k) {
      return (k.position_m - c[i]).norm() < tol;
    });
    ASSERT_NE(it, corners.end()) << "corner " << i;
    const double to_next = Direction(c[i], c[(i + 1) % 4]);
    const double to_prev = Direction(c[i], c[(i + 3) % 4]);
    const auto& a = it->line_angles_rad;
    const bool match =
        (AngleDistance(a[0], to_next) < angle_tol && AngleDistance(a[1], to_prev) < angle_tol) ||
        (AngleDistance(a[0], to_prev) < angle_tol && AngleDistance(a[1], to_next) < angle_tol);
    EXPECT_TRUE(match) << "corner " << i << ": " << a[0] << ", " << a[1];
    for (double v : a) {
      EXPECT_GT(v, -kPi);
      EXPECT_LE(v, kPi);
    }
  }
}

TEST(GridStructure, RectangularRoomGivesItsFourWallsAndFourCorners) {
  OccupancyGrid grid = MakeGrid();
  // Corners on cell centres: the walls are exactly one row or column of cells.
  const auto c = DrawRoom(grid, {1.05, 2.05}, 0.0);
  const std::vector<GridLine> lines = ExtractGridLines(grid, Centre(c), 6.0);
  ExpectLinesAreTheWalls(lines, c, 1e-6);
  for (const GridLine& l : lines) {
    EXPECT_TRUE(std::abs(l.angle_rad) < 1e-9 || std::abs(l.angle_rad - kPi / 2.0) < 1e-9);
    // Every cell of the wall, its two corner cells included (they are shared with the walls
    // found before).
    EXPECT_EQ(l.cells, static_cast<int>(std::lround(l.LengthM() / kRes)) + 1);
  }
  // Strongest first: the 6 m walls (61 cells) before the 4 m ones.
  EXPECT_NEAR(lines[0].LengthM(), 6.0, 1e-6);
  EXPECT_NEAR(lines[1].LengthM(), 6.0, 1e-6);
  const std::vector<GridCorner> corners = ExtractGridCorners(lines);
  ExpectCornersAreTheRoomsCorners(corners, c, 0.15, 1e-9);
  // Spelled out for the lower-left corner: its arms point along the walls, at 0 and π/2.
  const auto lower_left = std::find_if(corners.begin(), corners.end(), [&](const GridCorner& k) {
    return (k.position_m - c[0]).norm() < 0.15;
  });
  ASSERT_NE(lower_left, corners.end());
  std::array<double, 2> arms = lower_left->line_angles_rad;
  std::sort(arms.begin(), arms.end());
  EXPECT_NEAR(arms[0], 0.0, 1e-9);
  EXPECT_NEAR(arms[1], kPi / 2.0, 1e-9);
}

TEST(GridStructure, RotatedAndShiftedRoomGivesTheCornersMovedWithIt) {
  OccupancyGrid grid = MakeGrid();
  const auto c = DrawRoom(grid, {-3.37, 1.81}, 0.5);
  const std::vector<GridLine> lines = ExtractGridLines(grid, Centre(c), 6.0);
  // The supercover of a turned wall is up to two cells wide: its ends and fit within 1.5 cells.
  ExpectLinesAreTheWalls(lines, c, 0.15);
  for (const GridLine& l : lines) {
    EXPECT_LT(std::abs(std::remainder(l.angle_rad - 0.5, kPi / 2.0)), 0.02);  // 0.5 + k·π/2
  }
  ExpectCornersAreTheRoomsCorners(ExtractGridCorners(lines), c, 0.15, 0.02);
}

TEST(GridStructure, OnlyCellsInsideTheDiscAreUsed) {
  OccupancyGrid grid = MakeGrid();
  const auto near = DrawRoom(grid, {1.05, 2.05}, 0.0);
  const auto far = DrawRoom(grid, {30.05, 2.05}, 0.0);
  ExpectLinesAreTheWalls(ExtractGridLines(grid, Centre(near), 8.0), near, 1e-6);
  ExpectLinesAreTheWalls(ExtractGridLines(grid, Centre(far), 8.0), far, 1e-6);
  EXPECT_TRUE(ExtractGridLines(grid, {17.0, 4.0}, 8.0).empty());     // between the rooms
  EXPECT_TRUE(ExtractGridLines(grid, {500.0, -80.0}, 50.0).empty());  // off the written map
  EXPECT_TRUE(ExtractGridLines(grid, Centre(near), 0.0).empty());

  // A wall crossing the disc: only the part inside. Cells on y = 0.05, disc about (0.05, 3.05) of
  // radius 5: the cell centres with |x − 0.05| ≤ 4.
  OccupancyGrid wall = MakeGrid();
  DrawWall(wall, {-9.95, 0.05}, {9.95, 0.05});
  const std::vector<GridLine> part = ExtractGridLines(wall, {0.05, 3.05}, 5.0);
  ASSERT_EQ(part.size(), 1u);
  EXPECT_NEAR(part[0].start_m.x(), -3.95, 1e-6);
  EXPECT_NEAR(part[0].end_m.x(), 4.05, 1e-6);
  EXPECT_NEAR(part[0].start_m.y(), 0.05, 1e-6);
  EXPECT_EQ(part[0].cells, 81);
}

TEST(GridStructure, EmptyGridAndIsolatedCellsGiveNoLines) {
  const OccupancyGrid empty = MakeGrid();
  EXPECT_TRUE(ExtractGridLines(empty, {0.0, 0.0}, 10.0).empty());
  EXPECT_TRUE(ExtractGridCorners({}).empty());

  // A lattice of single cells 0.5 m apart: rows of 21 collinear cells make strong Hough peaks,
  // but every gap exceeds max_gap_m, so no run is a wall.
  OccupancyGrid lattice = MakeGrid();
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) lattice.Update({5 * i, 5 * j}, 3.0f);
  }
  EXPECT_TRUE(ExtractGridLines(lattice, {5.0, 5.0}, 10.0).empty());

  OccupancyGrid scattered = MakeGrid();
  Rng rng(4);
  for (int i = 0; i < 300; ++i) {
    scattered.Update(scattered.WorldToCell({rng.Uniform(0.0, 10.0), rng.Uniform(0.0, 10.0)}), 3.0f);
  }
  EXPECT_TRUE(ExtractGridLines(scattered, {5.0, 5.0}, 10.0).empty());
}

TEST(GridStructure, OnlyCellsAboveTheOccupiedProbabilityVote) {
  // A free wall, and a weakly occupied one (log-odds 0.5: p = 0.62 < 0.65).
  OccupancyGrid grid = MakeGrid();
  DrawWall(grid, {0.05, 0.05}, {5.05, 0.05}, -3.0f);
  DrawWall(grid, {0.05, 2.05}, {5.05, 2.05}, 0.5f);
  EXPECT_TRUE(ExtractGridLines(grid, {2.5, 1.0}, 5.0).empty());
  GridStructureParams lenient;
  lenient.occupied_probability = 0.6;
  const std::vector<GridLine> weak = ExtractGridLines(grid, {2.5, 1.0}, 5.0, lenient);
  ASSERT_EQ(weak.size(), 1u);
  EXPECT_NEAR(weak[0].start_m.y(), 2.05, 1e-6);

  // A room whose inside is free space: the free cells change nothing.
  OccupancyGrid room = MakeGrid();
  const auto c = DrawRoom(room, {1.05, 2.05}, 0.0);
  const std::vector<GridLine> walls_only = ExtractGridLines(room, Centre(c), 6.0);
  for (int x = 11; x < 70; ++x) {
    for (int y = 21; y < 60; ++y) room.Update({x, y}, -2.0f);
  }
  const std::vector<GridLine> with_free = ExtractGridLines(room, Centre(c), 6.0);
  ExpectLinesAreTheWalls(with_free, c, 1e-6);
  ASSERT_EQ(with_free.size(), walls_only.size());
  for (std::size_t i = 0; i < with_free.size(); ++i) EXPECT_EQ(with_free[i].cells, walls_only[i].cells);
}

TEST(GridStructure, DoorwaySplitsAWallButANarrowGapDoesNot) {
  OccupancyGrid door = MakeGrid();
  DrawWall(door, {0.05, 0.05}, {4.05, 0.05});
  DrawWall(door, {5.05, 0.05}, {10.05, 0.05});
  const std::vector<GridLine> lines = ExtractGridLines(door, {5.0, 0.0}, 6.0);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NEAR(lines[0].start_m.x(), 0.05, 1e-6);
  EXPECT_NEAR(lines[0].end_m.x(), 4.05, 1e-6);
  EXPECT_NEAR(lines[1].start_m.x(), 5.05, 1e-6);
  EXPECT_NEAR(lines[1].end_m.x(), 10.05, 1e-6);
  // Two collinear segments are no corner.
  EXPECT_TRUE(ExtractGridCorners(lines).empty());

  OccupancyGrid crack = MakeGrid();  // one missing cell: 0.2 m between centres ≤ max_gap_m
  DrawWall(crack, {0.05, 0.05}, {4.05, 0.05});
  DrawWall(crack, {4.25, 0.05}, {10.05, 0.05});
  const std::vector<GridLine> whole = ExtractGridLines(crack, {5.0, 0.0}, 6.0);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_NEAR(whole[0].LengthM(), 10.0, 1e-6);
  EXPECT_EQ(whole[0].cells, 100);
}

TEST(GridStructure, BudgetKeepsTheStrongestLines) {
  OccupancyGrid grid = MakeGrid();
  const auto c = DrawRoom(grid, {1.05, 2.05}, 0.0);
  GridStructureParams p;
  p.max_lines = 2;
  const std::vector<GridLine> lines = ExtractGridLines(grid, Centre(c), 6.0, p);
  ASSERT_EQ(lines.size(), 2u);
  for (const GridLine& l : lines) EXPECT_NEAR(l.LengthM(), 6.0, 1e-6);
}

TEST(GridStructure, CornersNeedEnoughAngleAndNearbyEnds) {
  auto line = [](Eigen::Vector2d a, Eigen::Vector2d b) {
    if (b.x() < a.x() || (b.x() == a.x() && b.y() < a.y())) std::swap(a, b);
    const Eigen::Vector2d d = b - a;
    return GridLine{a, b, std::atan2(d.y(), d.x()), 0};
  };
  const GridLine base = line({0.0, 0.0}, {3.0, 0.0});
  // An L at (3, 0) with a 0.3 m gap: one corner, arms toward (0, 0) and up the other wall.
  const auto l = ExtractGridCorners({base, line({3.0, 0.3}, {3.0, 2.0})});
  ASSERT_EQ(l.size(), 1u);
  EXPECT_TRUE(l[0].position_m.isApprox(Eigen::Vector2d(3.0, 0.0), 1e-12));
  EXPECT_NEAR(l[0].line_angles_rad[0], kPi, 1e-12);
  EXPECT_NEAR(l[0].line_angles_rad[1], kPi / 2.0, 1e-12);
  // 20° apart (less than 30°): no corner; 40°: a corner.
  const Eigen::Vector2d e20(std::cos(DegToRad(20.0)), std::sin(DegToRad(20.0)));
  const Eigen::Vector2d e40(std::cos(DegToRad(40.0)), std::sin(DegToRad(40.0)));
  EXPECT_TRUE(ExtractGridCorners({base, line({0.0, 0.0}, 2.0 * e20)}).empty());
  EXPECT_EQ(ExtractGridCorners({base, line({0.0, 0.0}, 2.0 * e40)}).size(), 1u);
  // Ends 0.5 m from the intersection (more than corner_max_gap_m): no corner.
  EXPECT_TRUE(ExtractGridCorners({base, line({3.5, 0.5}, {3.5, 2.0})}).empty());
  // A T-junction (the intersection in the middle of one segment): no corner.
  EXPECT_TRUE(ExtractGridCorners({base, line({1.5, 0.1}, {1.5, 2.0})}).empty());
  // Three walls meeting at one point give one corner, of the first pair.
  const auto merged = ExtractGridCorners(
      {base, line({0.0, 0.1}, {0.0, 2.0}), line({0.0, 0.0}, -2.0 * e40)});
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_NEAR(merged[0].line_angles_rad[1], kPi / 2.0, 1e-12);
}

TEST(GridStructure, SameInputGivesTheSameOutput) {
  OccupancyGrid grid = MakeGrid();
  const auto c = DrawRoom(grid, {-3.37, 1.81}, 0.5);
  DrawRoom(grid, {2.0, -1.0}, -1.1, 3.0, 2.0);
  Rng rng(9);
  for (int i = 0; i < 200; ++i) {
    grid.Update(grid.WorldToCell({rng.Uniform(-8.0, 8.0), rng.Uniform(-8.0, 8.0)}), 3.0f);
  }
  const OccupancyGrid copy = grid;
  const std::vector<GridLine> a = ExtractGridLines(grid, Centre(c), 12.0);
  const std::vector<GridLine> b = ExtractGridLines(copy, Centre(c), 12.0);
  ASSERT_GE(a.size(), 8u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].start_m, b[i].start_m);
    EXPECT_EQ(a[i].end_m, b[i].end_m);
    EXPECT_EQ(a[i].angle_rad, b[i].angle_rad);
    EXPECT_EQ(a[i].cells, b[i].cells);
  }
  const std::vector<GridCorner> ca = ExtractGridCorners(a), cb = ExtractGridCorners(b);
  ASSERT_GE(ca.size(), 8u);
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t i = 0; i < ca.size(); ++i) {
    EXPECT_EQ(ca[i].position_m, cb[i].position_m);
    EXPECT_EQ(ca[i].line_angles_rad, cb[i].line_angles_rad);
  }
}

}  // namespace
}  // namespace slamkit
