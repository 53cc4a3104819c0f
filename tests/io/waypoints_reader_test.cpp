#include "slamkit/io/waypoints_reader.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

using testing::Contains;
using testing::InputErrorOf;

class WaypointsReader : public testing::TempDirTest {};

TEST_F(WaypointsReader, ReadsPairsSkippingCommentsAndBlankLines) {
  const auto path = WriteFile("route.txt", "# x y\n1.5 2\n\n  -3\t4e1  \r\n# end\n0 0\n");
  const std::vector<Eigen::Vector2d> waypoints = ReadWaypoints(path);
  ASSERT_EQ(waypoints.size(), 3u);
  EXPECT_EQ(waypoints[0], Eigen::Vector2d(1.5, 2.0));
  EXPECT_EQ(waypoints[1], Eigen::Vector2d(-3.0, 40.0));
  EXPECT_EQ(waypoints[2], Eigen::Vector2d(0.0, 0.0));
}

TEST_F(WaypointsReader, ErrorsNameTheFileLineAndField) {
  const std::pair<std::string, std::string> cases[] = {
      {"1 2\n3 x\n", "route.txt:2: field 'y': not a number ('x')"},
      {"1 2\nnan 3\n", "route.txt:2: field 'x': not a finite number ('nan')"},
      {"1 2\n\n3 4 5\n", "route.txt:3: expected 2 fields"},
      {"1 2\n3\n", "route.txt:2: expected 2 fields"},
      {"# only\n1 2\n", "at least 2 waypoints, got 1"},
      {"", "route.txt: a route needs at least 2 waypoints, got 0"},
      {"# only\n\n", "route.txt: a route needs at least 2 waypoints, got 0"}};
  for (const auto& [text, part] : cases) {
    const auto path = WriteFile("route.txt", text);
    const std::string message = InputErrorOf([&] { ReadWaypoints(path); });
    EXPECT_TRUE(Contains(message, part)) << text;
  }
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadWaypoints(dir_ / "none.txt"); }),
                       "none.txt: cannot open file"));
}

}  // namespace
}  // namespace slamkit
