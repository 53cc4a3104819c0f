#include "slamkit/io/landmark_csv.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "slamkit/io/error.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::Contains;

class LandmarkCsv : public testing::TempDirTest {
 protected:
  fs::path Write(const std::string& text) const { return WriteFile("landmarks.csv", text); }
  // The message of the InputError that reading `text` raises.
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadLandmarkCsv(Write(text)); });
  }
};

TEST_F(LandmarkCsv, ReadsHeaderCommentsBlankLinesAndSpaces) {
  const LandmarkWorld world =
      ReadLandmarkCsv(Write("# trees\nid,x_m,y_m\n\n3, 1.5 ,-2\r\n# more\n7,1e2,0.25\n  \n"));
  ASSERT_EQ(world.landmarks.size(), 2u);
  EXPECT_EQ(world.landmarks[0].id, 3);
  EXPECT_EQ(world.landmarks[0].position_m, Eigen::Vector2d(1.5, -2.0));
  EXPECT_EQ(world.landmarks[1].id, 7);
  EXPECT_EQ(world.landmarks[1].position_m, Eigen::Vector2d(100.0, 0.25));
}

TEST_F(LandmarkCsv, HeaderIsOptional) {
  const LandmarkWorld world = ReadLandmarkCsv(Write("0,1,2\n1,3,4"));
  ASSERT_EQ(world.landmarks.size(), 2u);
  EXPECT_EQ(world.landmarks[1].position_m, Eigen::Vector2d(3.0, 4.0));
}

TEST_F(LandmarkCsv, NanNamesFileLineAndField) {
  const std::string message = ErrorOf("id,x_m,y_m\n0,1,2\n\n1,nan,3\n");
  EXPECT_TRUE(Contains(message, "landmarks.csv:4:"));
  EXPECT_TRUE(Contains(message, "field 'x_m'"));
  EXPECT_TRUE(Contains(message, "'nan'"));
  EXPECT_TRUE(Contains(ErrorOf("0,1,inf\n"), "landmarks.csv:1: field 'y_m': not a finite number"));
}

TEST_F(LandmarkCsv, MissingAndBadFields) {
  EXPECT_TRUE(Contains(ErrorOf("id,x_m,y_m\n0,1\n"), "landmarks.csv:2: field 'y_m': missing"));
  EXPECT_TRUE(Contains(ErrorOf("0,,2\n"), "landmarks.csv:1: field 'x_m'"));
  EXPECT_TRUE(Contains(ErrorOf("0,1,2,3\n"), "landmarks.csv:1: expected 3 fields"));
  EXPECT_TRUE(Contains(ErrorOf("a,1,2\n"), "landmarks.csv:1: field 'id': not an integer"));
  EXPECT_TRUE(Contains(ErrorOf("0,1,2\n1.5,1,2\n"), "landmarks.csv:2: field 'id'"));
  EXPECT_TRUE(Contains(ErrorOf("0,1,2\n1,2x,2\n"), "landmarks.csv:2: field 'x_m': not a number"));
  EXPECT_TRUE(Contains(ErrorOf("-3,1,2\n"), "landmarks.csv:1: field 'id'"));
}

TEST_F(LandmarkCsv, DuplicateIdNamesBothLines) {
  const std::string message = ErrorOf("id,x_m,y_m\n5,0,0\n6,1,1\n5,2,2\n");
  EXPECT_TRUE(Contains(message, "landmarks.csv:4:"));
  EXPECT_TRUE(Contains(message, "duplicate id 5"));
  EXPECT_TRUE(Contains(message, "line 2"));
}

// Issue 8 item 11: nothing to process is an input error saying what was expected.
TEST_F(LandmarkCsv, EmptyInputIsAnError) {
  for (const char* text : {"", "# only a comment\n\n", "id,x_m,y_m\n"}) {
    EXPECT_TRUE(Contains(ErrorOf(text), "landmarks.csv: no landmarks (expected `id,x_m,y_m`"))
        << text;
  }
}

TEST_F(LandmarkCsv, MissingFileNamesIt) {
  const fs::path path = dir_ / "absent.csv";
  try {
    ReadLandmarkCsv(path);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(std::string(e.what()), path.string()));
  }
}

}  // namespace
}  // namespace slamkit
