#include "slamkit/io/pose_graph_io.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "slamkit/io/error.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::Contains;

const fs::path kPoseGraphs = fs::path(SLAMKIT_DATASETS_DIR) / "posegraphs";

// Two vertices and an edge between them, each a line of its own.
constexpr const char* kVertex0 = "VERTEX_SE2 0 0 0 0\n";
constexpr const char* kVertex1 = "VERTEX_SE2 1 1 0 0.1\n";
constexpr const char* kEdge01 = "EDGE_SE2 0 1 1 0 0.1 1 0 0 1 0 1\n";

bool SameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// A graph whose numbers use all 53 bits of their mantissas, over many magnitudes, with signed
// zeros, angles at the wrap boundary and full (symmetric, positive definite) information.
PoseGraph RandomGraph(int vertices, int edges) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  auto number = [&] { return std::ldexp(unit(rng), exponent(rng)); };
  PoseGraph g;
  for (int i = 0; i < vertices; ++i) {
    g.vertices.push_back({3 * i - 7, Pose2(number(), number(), std::numbers::pi * unit(rng))});
  }
  g.vertices[0].pose = Pose2(-0.0, 0.0, -std::numbers::pi);
  for (int i = 0; i < edges; ++i) {
    PoseGraphEdge e{g.vertices[i % vertices].id, g.vertices[(i * 7 + 1) % vertices].id,
                    Pose2(number(), number(), number()), Eigen::Matrix3d::Identity()};
    Eigen::Matrix3d a;
    for (double& x : a.reshaped()) x = number();
    const Eigen::Matrix3d spd = a.transpose() * a + a.squaredNorm() * Eigen::Matrix3d::Identity();
    e.information = spd.selfadjointView<Eigen::Upper>();  // symmetric to the bit
    if (e.from != e.to) g.edges.push_back(e);
  }
  return g;
}

void ExpectSameBits(const Pose2& a, const Pose2& b) {
  EXPECT_TRUE(SameBits(a.x(), b.x()) && SameBits(a.y(), b.y()) && SameBits(a.theta(), b.theta()))
      << a.vector().transpose() << " vs " << b.vector().transpose();
}

void ExpectSameGraph(const PoseGraph& a, const PoseGraph& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    EXPECT_EQ(a.vertices[i].id, b.vertices[i].id);
    ExpectSameBits(a.vertices[i].pose, b.vertices[i].pose);
  }
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].from, b.edges[i].from);
    EXPECT_EQ(a.edges[i].to, b.edges[i].to);
    ExpectSameBits(a.edges[i].measurement, b.edges[i].measurement);
    for (int k = 0; k < 9; ++k) {
      EXPECT_TRUE(
          SameBits(a.edges[i].information.reshaped()(k), b.edges[i].information.reshaped()(k)))
          << "edge " << i << " information entry " << k;
    }
  }
}

class PoseGraphIo : public testing::TempDirTest {
 protected:
  fs::path Write(const std::string& text) const { return WriteFile("graph.g2o", text); }
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadPoseGraph(Write(text)); });
  }
};

TEST_F(PoseGraphIo, G2oRoundTripIsExactToTheBit) {
  const PoseGraph graph = RandomGraph(50, 120);
  WritePoseGraphG2o(dir_ / "out.g2o", graph);
  ExpectSameGraph(ReadPoseGraph(dir_ / "out.g2o"), graph);
  const std::string text = testing::ReadText(dir_ / "out.g2o");
  EXPECT_TRUE(text.starts_with("VERTEX_SE2 -7 -0 0 -3.1415926535897931\n")) << text.substr(0, 80);
  EXPECT_EQ(text.find("VERTEX_SE2", text.find("EDGE_SE2")), std::string::npos);
  // Nothing but the file: the temporary was renamed.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(PoseGraphIo, WriteFailureNamesThePath) {
  try {
    WritePoseGraphG2o(dir_ / "absent" / "out.g2o", RandomGraph(3, 2));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(Contains(e.what(), "absent/out.g2o"));
  }
}

// The same full information matrix in each format's order of entries.
TEST_F(PoseGraphIo, ToroAndG2oVersionsReadEqual) {
  Eigen::Matrix3d information;
  information << 10, 1, 2, 1, 20, 3, 2, 3, 30;
  const PoseGraph g2o = ReadPoseGraph(WriteFile(
      "a.g2o", "VERTEX_SE2 4 0 0 0\nVERTEX_SE2 9 1 2 0.5\nEDGE_SE2 4 9 1 2 0.5 10 1 2 20 3 30\n"));
  const PoseGraph toro = ReadPoseGraph(WriteFile(
      "a.graph", "VERTEX2 4 0 0 0\nVERTEX2 9 1 2 0.5\nEDGE2 4 9 1 2 0.5 10 1 20 30 2 3\n"));
  ExpectSameGraph(toro, g2o);
  ASSERT_EQ(toro.edges.size(), 1u);
  EXPECT_EQ(toro.edges[0].information, information);
  EXPECT_EQ(toro.edges[0].from, 4);
  EXPECT_EQ(toro.edges[0].to, 9);
  EXPECT_EQ(toro.vertices[1].pose.vector(), Eigen::Vector3d(1, 2, 0.5));
}

TEST_F(PoseGraphIo, SkipsCommentsAndIgnoresFixAndEquiv) {
  const PoseGraph g = ReadPoseGraph(Write("# a comment\r\n\r\n" + std::string(kEdge01) +
                                          "FIX 0\r\n  EQUIV 1 0\n\t" + kVertex1 + kVertex0));
  ASSERT_EQ(g.vertices.size(), 2u);
  EXPECT_EQ(g.vertices[0].id, 1);  // the VERTEX lines' order, after the edge that names them
  EXPECT_EQ(g.vertices[1].id, 0);
  ASSERT_EQ(g.edges.size(), 1u);
  EXPECT_EQ(g.edges[0].measurement.vector(), Eigen::Vector3d(1, 0, 0.1));
  EXPECT_EQ(g.edges[0].information, Eigen::Matrix3d::Identity());
}

TEST_F(PoseGraphIo, EdgesAloneGiveIdentityVerticesInIdOrder) {
  const PoseGraph g = ReadPoseGraph(Write("EDGE2 5 2 1 0 0 1 0 1 1 0 0\n" + std::string(kEdge01)));
  constexpr std::array kIds = {0, 1, 2, 5};
  ASSERT_EQ(g.vertices.size(), kIds.size());
  for (std::size_t i = 0; i < kIds.size(); ++i) {
    EXPECT_EQ(g.vertices[i].id, kIds[i]);
    EXPECT_EQ(g.vertices[i].pose.vector(), Eigen::Vector3d::Zero());
  }
  EXPECT_EQ(g.edges.size(), 2u);
}

TEST_F(PoseGraphIo, RejectsMalformedLinesNamingLineAndField) {
  const std::string ok = std::string(kVertex0) + kVertex1;  // lines 1 and 2
  const auto error = [&](const std::string& line) { return ErrorOf(ok + line); };
  EXPECT_TRUE(Contains(error("VERTEX_XY 2 1 1\n"),
                       "graph.g2o:3: field 'tag': unknown tag 'VERTEX_XY' (expected VERTEX_SE2"));
  EXPECT_TRUE(Contains(error("EDGE_SE2 0 1 1 0 0 1 0 0 1 0\n"),
                       "graph.g2o:3: EDGE_SE2 field 'I33': missing"));
  EXPECT_TRUE(
      Contains(error("EDGE2 0 1 1 0 0 1 0 1 1 0\n"), "graph.g2o:3: EDGE2 field 'I23': missing"));
  EXPECT_TRUE(Contains(error("VERTEX_SE2 2 1 1 0 7\n"),
                       "graph.g2o:3: VERTEX_SE2 field 'theta': followed by an extra field ('7'"));
  EXPECT_TRUE(Contains(error("EDGE_SE2 0 1 1 0 0 1 0 0 abc 0 1\n"),
                       "graph.g2o:3: EDGE_SE2 field 'I22': not a number ('abc')"));
  EXPECT_TRUE(Contains(error("EDGE_SE2 0 1 nan 0 0 1 0 0 1 0 1\n"),
                       "graph.g2o:3: EDGE_SE2 field 'dx': not a finite number ('nan')"));
  EXPECT_TRUE(Contains(error("VERTEX2 2 0 -inf 0\n"),
                       "graph.g2o:3: VERTEX2 field 'y': not a finite number ('-inf')"));
  EXPECT_TRUE(Contains(error("EDGE_SE2 0 1.5 1 0 0 1 0 0 1 0 1\n"),
                       "graph.g2o:3: EDGE_SE2 field 'id2': not an integer id ('1.5')"));
  EXPECT_TRUE(Contains(error("FIX 0 x\n"), "graph.g2o:3: FIX field 'id': not an integer id ('x')"));
  EXPECT_TRUE(Contains(error("EQUIV 0\n"), "graph.g2o:3: EQUIV field 'id2': missing"));
}

TEST_F(PoseGraphIo, RejectsInconsistentGraphsNamingLineAndField) {
  const std::string ok = std::string(kVertex0) + kVertex1;
  EXPECT_TRUE(Contains(ErrorOf(ok + "VERTEX2 0 5 5 0\n"),
                       "graph.g2o:3: VERTEX2 field 'id': duplicate vertex id 0 (first on line 1)"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "EDGE_SE2 1 1 0 0 0 1 0 0 1 0 1\n"),
                       "graph.g2o:3: EDGE_SE2 field 'id2': an edge from vertex 1 to itself"));
  // An edge may come before its vertices, but every vertex it names needs a VERTEX line.
  EXPECT_TRUE(Contains(ErrorOf("EDGE2 7 0 1 0 0 1 0 1 1 0 0\n" + ok),
                       "graph.g2o:1: EDGE2 field 'id1': no VERTEX line for vertex 7"));
  EXPECT_TRUE(Contains(ErrorOf(ok + kEdge01 + "EDGE_SE2 1 3 1 0 0 1 0 0 1 0 1\n"),
                       "graph.g2o:4: EDGE_SE2 field 'id2': no VERTEX line for vertex 3"));
  // Found at the end of the file, long after the reader's buffer dropped the edge's line.
  std::string vertices;
  for (int id = 0; id < 6000; ++id) vertices += fmt::format("VERTEX_SE2 {} 0 0 0\n", id + 8);
  EXPECT_TRUE(Contains(ErrorOf("EDGE2 7 8 1 0 0 1 0 1 1 0 0\n" + vertices),
                       "graph.g2o:1: EDGE2 field 'id1': no VERTEX line for vertex 7"));
}

TEST_F(PoseGraphIo, RejectsInformationThatIsNotPositiveDefinite) {
  const std::string ok = std::string(kVertex0) + kVertex1;
  EXPECT_TRUE(Contains(ErrorOf(ok + "EDGE_SE2 0 1 1 0 0 1 2 0 1 0 1\n"),
                       "graph.g2o:3: EDGE_SE2 field 'information': not positive definite (g2o "
                       "order I11 I12 I13 I22 I23 I33: 1 2 0 1 0 1)"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 0\n"),
                       "graph.g2o:3: EDGE_SE2 field 'information': not positive definite"));
  // A TORO diagonal read as g2o puts a zero at I33; a g2o diagonal read as TORO, at I22.
  EXPECT_TRUE(Contains(ErrorOf(ok + "EDGE_SE2 0 1 1 0 0 1 0 1 1 0 0\n"),
                       "graph.g2o:3: EDGE_SE2 field 'information': not positive definite"));
  const std::string toro = ErrorOf(ok + "EDGE2 0 1 1 0 0 3 0 0 3 0 5\n");
  EXPECT_TRUE(Contains(toro,
                       "graph.g2o:3: EDGE2 field 'information': not positive definite "
                       "(TORO order I11 I12 I22 I33 I13 I23: 3 0 0 3 0 5); positive "
                       "definite in g2o order"));
  EXPECT_FALSE(Contains(ErrorOf(ok + "EDGE2 0 1 1 0 0 1 0 0 1 0 0\n"), "in g2o order"));
}

TEST_F(PoseGraphIo, RejectsFilesWithoutAGraph) {
  EXPECT_TRUE(Contains(ErrorOf(""), "graph.g2o: no vertex and no edge"));
  EXPECT_TRUE(Contains(ErrorOf("# FIX 0\n\n  \nFIX 0\n"), "graph.g2o: no vertex and no edge"));
  EXPECT_TRUE(Contains(ErrorOf(std::string("\x89PNG\r\n\x1a\n\0\0", 10)),
                       "graph.g2o:1: field 'tag': unknown tag '\\x89PNG'"));
  EXPECT_TRUE(Contains(ErrorOf(std::string("\x7f"
                                           "ELF\x02\x01\x01\0\0",
                                           9)),
                       "graph.g2o:1: not a text file (byte \\x7f at column 1)"));
  EXPECT_TRUE(Contains(ErrorOf(kVertex0 + std::string("VERTEX_SE2 1 0\0 0 0\n", 20)),
                       "graph.g2o:2: not a text file (byte \\x00 at column 15)"));
  EXPECT_TRUE(Contains(ErrorOf("\xff\xfe VERTEX_SE2\n"),
                       "graph.g2o:1: field 'tag': unknown tag '\\xff\\xfe'"));
  EXPECT_TRUE(Contains(testing::InputErrorOf([&] { ReadPoseGraph(dir_ / "absent.g2o"); }),
                       "absent.g2o: cannot open file"));
}

// The data sets of ../shared/datasets/posegraphs, with the counts of their VERTEX and EDGE lines
// (a file without VERTEX lines has a vertex per id its edges name); each round-trips exactly.
TEST_F(PoseGraphIo, DatasetsReadWithTheirCounts) {
  if (!fs::exists(kPoseGraphs / "intel.g2o")) GTEST_SKIP() << "no " << kPoseGraphs;
  const struct {
    const char* name;
    std::size_t vertices;
    std::size_t edges;
  } kFiles[] = {{"intel.g2o", 1728, 2512},       {"MIT.g2o", 808, 827},
                {"CSAIL.g2o", 1045, 1172},       {"manhattan.g2o", 3500, 5453},
                {"city10000.g2o", 10000, 20687}, {"ais2klinik.g2o", 15115, 16727},
                {"w100.graph", 100, 300}};
  for (const auto& f : kFiles) {
    const PoseGraph g = ReadPoseGraph(kPoseGraphs / f.name);
    EXPECT_EQ(g.vertices.size(), f.vertices) << f.name;
    EXPECT_EQ(g.edges.size(), f.edges) << f.name;
    WritePoseGraphG2o(dir_ / f.name, g);
    ExpectSameGraph(ReadPoseGraph(dir_ / f.name), g);
  }
  // VERTEX_SE2 1 0.144012 -0.004462 -0.017453 and the first edge of intel.g2o.
  const PoseGraph intel = ReadPoseGraph(kPoseGraphs / "intel.g2o");
  EXPECT_EQ(intel.vertices[1].pose.vector(), Eigen::Vector3d(0.144012, -0.004462, -0.017453));
  EXPECT_EQ(intel.edges[0].from, 0);
  EXPECT_EQ(intel.edges[0].to, 1);
}

// w20000.txt has EDGE2 lines whose entries (3.16228 0 0 3.16228 0 5) are a diagonal in g2o order
// and no information matrix in TORO order.
TEST(PoseGraphIoDatasets, W20000HasG2oOrderUnderTheToroTag) {
  if (!fs::exists(kPoseGraphs / "w20000.txt")) GTEST_SKIP() << "no " << kPoseGraphs;
  EXPECT_TRUE(Contains(testing::InputErrorOf([] { ReadPoseGraph(kPoseGraphs / "w20000.txt"); }),
                       "w20000.txt:1: EDGE2 field 'information': not positive definite (TORO "
                       "order I11 I12 I22 I33 I13 I23: 3.16228 0 0 3.16228 0 5); positive "
                       "definite in g2o order"));
}

}  // namespace
}  // namespace slamkit
