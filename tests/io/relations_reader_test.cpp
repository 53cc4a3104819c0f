#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/relations_reader.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::Contains;

const fs::path kRelationsCarmenDir = fs::path(SLAMKIT_DATASETS_DIR) / "carmen";

class RelationsReader : public testing::TempDirTest {
 protected:
  fs::path Write(const std::string& text) const { return WriteFile("log.relations", text); }
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadRelations(Write(text)); });
  }
};

TEST_F(RelationsReader, ReadsIntelRelations) {
  const std::vector<PoseRelation> relations = ReadRelations(kRelationsCarmenDir / "intel.relations");
  ASSERT_EQ(relations.size(), 2984u);
  // 976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 -1.682210
  EXPECT_EQ(relations[0].t1_s, 976052905.167303);
  EXPECT_EQ(relations[0].t2_s, 976052911.885496);
  EXPECT_EQ(relations[0].delta.vector(), Eigen::Vector3d(-0.056990, -0.128430, -1.682210));
  // 976054744.377487 976055538.433137 0.881540 0.001790 0.000000 0.000000 0.000000 0.075760
  EXPECT_EQ(relations.back().t2_s, 976055538.433137);
  EXPECT_EQ(relations.back().delta.vector(), Eigen::Vector3d(0.881540, 0.001790, 0.075760));

  // Every relation timestamp is the timestamp of an intel.clf scan, as parsed by ReadCarmenLog.
  const CarmenLog log = ReadCarmenLog(kRelationsCarmenDir / "intel.clf");
  std::vector<double> scan_times;
  for (const LaserScan& scan : log.scans) scan_times.push_back(scan.t_s);
  std::sort(scan_times.begin(), scan_times.end());
  int unmatched = 0;
  for (const PoseRelation& r : relations) {
    for (double t : {r.t1_s, r.t2_s}) {
      unmatched += std::binary_search(scan_times.begin(), scan_times.end(), t) ? 0 : 1;
    }
  }
  EXPECT_EQ(unmatched, 0);
}

TEST_F(RelationsReader, SkipsCommentsAndBlankLinesAndWrapsYaw) {
  const std::vector<PoseRelation> relations =
      ReadRelations(Write("# t1 t2 x y z roll pitch yaw\n\n  \n"
                          "1.5 2.5 0.3 -0.2 0 1e-7 -1e-7 0.1\n"
                          "2.5\t3.5 1 2 0 0 0 4\r\n"));
  ASSERT_EQ(relations.size(), 2u);
  EXPECT_EQ(relations[0].t1_s, 1.5);
  EXPECT_EQ(relations[0].t2_s, 2.5);
  EXPECT_EQ(relations[0].delta.vector(), Eigen::Vector3d(0.3, -0.2, 0.1));
  EXPECT_NEAR(relations[1].delta.theta(), 4.0 - 2.0 * M_PI, 1e-12);
}

// Issue 8 item 11: nothing to process is an input error saying what was expected.
TEST_F(RelationsReader, EmptyInputIsAnError) {
  for (const char* text : {"", "# t1 t2 x y z roll pitch yaw\n\n"}) {
    EXPECT_TRUE(Contains(ErrorOf(text), "log.relations: no relations (expected `t1 t2 x y z"))
        << text;
  }
}

TEST_F(RelationsReader, RejectsMalformedLinesWithTheirNumber) {
  const std::string ok = "# header\n1 2 0 0 0 0 0 0\n";
  EXPECT_TRUE(Contains(ErrorOf(ok + "1 2 0.5 abc 0 0 0 0\n"),
                       "log.relations:3: field 'y': not a number ('abc')"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "1 2 nan 0 0 0 0 0\n"),
                       "log.relations:3: field 'x': not a finite number ('nan')"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "1 2 0 0 0 0 0\n"), "log.relations:3: field 'yaw': missing"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "1 2 0 0 0 0 0 0 9\n"),
                       "log.relations:3: a line has 9 fields, expected 8"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "1 2 0 0 0.1 0 0 0\n"),
                       "log.relations:3: field 'z': must be 0 in a planar relation ('0.1')"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "1 2 0 0 0 0 -2e-6 0\n"), "log.relations:3: field 'pitch'"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "\n1 2 0 0 0 0.5 0 0\n"), "log.relations:4: field 'roll'"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "x 2 0 0 0 0 0 0\n"), "log.relations:3: field 't1'"));
}

TEST_F(RelationsReader, MissingFileNamesIt) {
  try {
    ReadRelations(dir_ / "absent.relations");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "absent.relations: cannot open file"));
  }
}

}  // namespace
}  // namespace slamkit
