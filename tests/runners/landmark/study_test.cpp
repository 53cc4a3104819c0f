// SPEC S2's experiment (RunStudy) on a short version of configs/swslam.yaml, and its files.
#include "slamkit/runners/landmark/study.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "runners/landmark/short_swslam.hpp"
#include "common/temp_dir.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/landmark/study_outputs.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

StudyParams Small() {
  StudyParams p;
  p.runs = 3;
  p.seed = 4;
  p.threads = 2;
  p.particles = 5;  // FastSLAM's figures are not what this test checks
  return p;
}

const StudyResult& ShortStudy() {
  static const StudyResult result = RunStudy(ShortSwslam(), Small());
  return result;
}

using testing::ReadText;

TEST(Study, RunsTheThreeMethodsOfTheSeedInItsOrder) {
  const StudyResult& r = ShortStudy();
  ASSERT_EQ(r.methods.size(), 3u);
  EXPECT_EQ(r.methods[0].key, "ekf_slam");
  EXPECT_EQ(r.methods[0].planner, PlannerKind::kRoute);
  EXPECT_EQ(r.methods[1].filter, FilterKind::kFastSlam2);
  EXPECT_EQ(r.methods[1].planner, PlannerKind::kRoute);
  EXPECT_EQ(r.methods[2].planner, PlannerKind::kSwslam);
  for (const StudyMethodResult& m : r.methods) {
    EXPECT_EQ(m.mc.run_count, 3) << m.key;
    EXPECT_EQ(m.traces.size(), 3u) << m.key;
    EXPECT_GT(m.wall_time_s, 0.0) << m.key;
    EXPECT_FALSE(m.sections.empty()) << m.key;
    EXPECT_GT(m.position_rms_m.mean, 0.0) << m.key;
    EXPECT_GT(m.position_rms_m.variance, 0.0) << m.key;
    double lo = 1e300, hi = 0.0;
    for (const RunSummary& s : m.mc.summaries) {
      lo = std::min(lo, s.anees);
      hi = std::max(hi, s.anees);
    }
    EXPECT_GE(m.anees_run_median, lo) << m.key;
    EXPECT_LE(m.anees_run_median, hi) << m.key;
  }
}

// The route methods drive the same true path with the same streams, so measured on the same
// (SWSLAM's) sections they count the same sightings; SWSLAM, sent into the cluster, sees each
// landmark of its sections at least as often as the route does in the same sections.
TEST(Study, RouteMethodsShareSectionsAndSwslamSeesLandmarksMoreOften) {
  const StudyResult& r = ShortStudy();
  const StudyMethodResult& ekf = r.methods[0];
  const StudyMethodResult& fastslam = r.methods[1];
  const StudyMethodResult& swslam = r.methods[2];
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_EQ(ekf.traces[k].sections.size(), swslam.traces[k].sections.size()) << k;
    ASSERT_EQ(fastslam.traces[k].sections.size(), swslam.traces[k].sections.size()) << k;
    for (std::size_t i = 0; i < swslam.traces[k].sections.size(); ++i) {
      const SectionStats& e = ekf.traces[k].sections[i];
      EXPECT_EQ(e.observations, fastslam.traces[k].sections[i].observations);
      EXPECT_EQ(e.section.route_waypoint, swslam.traces[k].sections[i].section.route_waypoint);
      EXPECT_GT(e.periods, 0);
    }
  }
  ASSERT_EQ(ekf.sections.size(), swslam.sections.size());
  for (std::size_t i = 0; i < swslam.sections.size(); ++i) {
    EXPECT_GE(swslam.sections[i].observations_per_landmark,
              ekf.sections[i].observations_per_landmark)
        << "section " << i + 1;
    EXPECT_GT(swslam.sections[i].periods, ekf.sections[i].periods) << "section " << i + 1;
  }
}

TEST(Study, BadParametersAreInputErrors) {
  StudyParams p = Small();
  p.runs = 0;
  EXPECT_THROW(RunStudy(ShortSwslam(), p), InputError);
  p = Small();
  p.particles = 0;
  EXPECT_THROW(RunStudy(ShortSwslam(), p), InputError);
  p = Small();
  p.fastslam = FilterKind::kEkf;
  EXPECT_THROW(RunStudy(ShortSwslam(), p), InputError);
}

class StudyFiles : public testing::TempDirTest {};

TEST_F(StudyFiles, WritesTheSeedsTablesWithOurFiguresBesideThePapers) {
  const StudyResult& r = ShortStudy();
  WriteStudyOutputs(dir_, ShortSwslam(), r);
  for (int t = 1; t <= 5; ++t) {
    const std::string csv = ReadText(dir_ / ("table" + std::to_string(t) + ".csv"));
    int rows = 0;
    for (char ch : csv) rows += ch == '\n' ? 1 : 0;
    EXPECT_EQ(rows, 4) << "table " << t;  // header and three methods
    for (const char* key : {"\nekf_slam,", "\nfastslam,", "\nswslam,"}) {
      EXPECT_NE(csv.find(key), std::string::npos) << "table " << t << ": " << key;
    }
  }
  // The paper's figures sit in the files: Table 2's SWSLAM row, Table 4's FastSLAM mean.
  EXPECT_NE(ReadText(dir_ / "table2.csv").find(",1765,33,46"), std::string::npos);
  const std::string md = ReadText(dir_ / "tables.md");
  for (const char* part : {"Table 1.", "Table 2.", "Table 3.", "Table 4.", "Table 5.", "0.5611",
                           "SWSLAM", "FastSLAM 2.0", "EKF-SLAM", "ANEES"}) {
    EXPECT_NE(md.find(part), std::string::npos) << part;
  }
  const nlohmann::json study = nlohmann::json::parse(ReadText(dir_ / "study.json"));
  ASSERT_EQ(study["methods"].size(), 3u);
  for (const nlohmann::json& m : study["methods"]) {
    for (const char* key : {"anees", "anees_fraction_in_band", "position_rmse_m", "sections",
                            "wall_time_s", "position_rms_m", "heading_rms_rad", "paper"}) {
      EXPECT_TRUE(m.contains(key)) << m["key"] << " " << key;
    }
    EXPECT_EQ(m["per_run"].size(), 3u);
  }
  EXPECT_EQ(study["methods"][2]["anees"].get<double>(), r.methods[2].mc.anees_mean);
  const nlohmann::json metrics = nlohmann::json::parse(ReadText(dir_ / "metrics.json"));
  EXPECT_FALSE(metrics["methods"][0].contains("per_run"));
  EXPECT_TRUE(fs::exists(dir_ / "nees.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "sections.csv"));
}

}  // namespace
}  // namespace slamkit
