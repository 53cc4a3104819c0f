#include "slamkit/io/floor_plan_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

using testing::Contains;
using testing::InputErrorOf;

class FloorPlanReader : public testing::TempDirTest {};

void ExpectWall(const WallSegment& wall, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  EXPECT_EQ(wall.first, a);
  EXPECT_EQ(wall.second, b);
}

TEST_F(FloorPlanReader, ReadsWallsAndClosesPolygons) {
  const auto path = WriteFile("plan.txt",
                              "# a square room and a wall\n"
                              "poly 0 0  4 0\t4 4 0 4   # counter-clockwise\r\n"
                              "\n"
                              "  1.5 -2 1.5 3e0\n");
  const Walls walls = ReadFloorPlanFile(path);
  ASSERT_EQ(walls.size(), 5u);
  ExpectWall(walls[0], {0, 0}, {4, 0});
  ExpectWall(walls[1], {4, 0}, {4, 4});
  ExpectWall(walls[2], {4, 4}, {0, 4});
  ExpectWall(walls[3], {0, 4}, {0, 0});  // the last point joins the first
  ExpectWall(walls[4], {1.5, -2}, {1.5, 3});
}

TEST_F(FloorPlanReader, ATriangleIsTheSmallestPolygon) {
  const Walls walls = ReadFloorPlanFile(WriteFile("plan.txt", "poly 0 0 1 0 0 1\n"));
  ASSERT_EQ(walls.size(), 3u);
  ExpectWall(walls[2], {0, 1}, {0, 0});
}

TEST_F(FloorPlanReader, ErrorsNameTheFileLineAndField) {
  const std::pair<std::string, std::string> cases[] = {
      {"0 0 1 0\n0 0 1\n", "plan.txt:2: expected 4 numbers `x1 y1 x2 y2`"},
      {"# c\n\n0 0 1 0 2\n", "plan.txt:3: expected 4 numbers `x1 y1 x2 y2`"},
      {"0 0 1 0\n0 0 x 1\n", "plan.txt:2: field 'x2': not a number ('x')"},
      {"0 0 1 0\n0 nan 1 1\n", "plan.txt:2: field 'y1': not a finite number ('nan')"},
      {"0 0 1 0\n0 0 1 -inf\n", "plan.txt:2: field 'y2': not a finite number ('-inf')"},
      {"0 0 1 0\n\n2 3 2 3\n", "plan.txt:3: field 'x2 y2': the same point as x1 y1"},
      {"poly 0 0 1 0 1 1 0\n", "plan.txt:1: poly has 7 numbers, expected `x y` pairs"},
      {"0 0 1 0\npoly 0 0 1 1\n", "plan.txt:2: poly has 2 points, needs at least 3"},
      {"poly\n", "plan.txt:1: poly has 0 points, needs at least 3"},
      {"\npoly 0 0 1 0 1 1 y 2\n", "plan.txt:2: poly field 'x4': not a number ('y')"},
      {"poly 0 0 1 0 1 1 0 inf\n", "plan.txt:1: poly field 'y4': not a finite number"},
      {"poly 0 0 1 0 1 0 0 1\n", "plan.txt:1: poly field 'x3 y3': the same point as x2 y2"},
      {"poly 0 0 1 0 1 1 0 0\n", "plan.txt:1: poly field 'x4 y4': the same point as x1 y1"},
      {"polygon 0 0 1 0 1 1\n", "plan.txt:1: expected 4 numbers"},
      {"# nothing but comments\n\n", "plan.txt: no walls"},
      {"", "plan.txt: no walls"}};
  for (const auto& [text, part] : cases) {
    const auto path = WriteFile("plan.txt", text);
    const std::string message = InputErrorOf([&] { ReadFloorPlanFile(path); });
    EXPECT_TRUE(Contains(message, part)) << text;
  }
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadFloorPlanFile(dir_ / "none.txt"); }),
                       "none.txt: cannot open file"));
}

}  // namespace
}  // namespace slamkit
