// `slamkit gridexplore` and `slamkit grid --predict` end to end (SPEC S4). Labelled slow: the
// filter runs in a closed loop with the explorer, ~100× slower under ASan than in Release.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

const fs::path kPlans = fs::path(SLAMKIT_SOURCE_DIR) / "examples" / "plans";

std::string FirstLine(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// The robot explores the room on its own estimate until no frontier is left: the explored map
// then covers the room (cell accuracy against the true map), and the estimate beats the noisy
// odometry it was driven with.
TEST(GridExplore, ExploresARoomToTheEndAndWritesTheContractFiles) {
  const fs::path dir = FreshDir("gridexplore_room");
  const auto r = RunCli("gridexplore --plan " + (kPlans / "room_with_pillar.txt").string() +
                        " --start 1.5,1.5,0 --predict on --particles 5 --max-time 600 "
                        "--odom-sigma-omega 0.1 --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"trajectory.txt", "trajectory.tum", "truth.tum", "truth.pgm", "map.pgm",
                           "map.yaml",
                           "map.png", "metrics.json", "hypotheses.csv", "predicted.pgm",
                           "predicted.yaml", "map_predicted.png"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const auto m = nlohmann::json::parse(ReadText(dir / "out" / "metrics.json"));
  EXPECT_TRUE(m["finished"].get<bool>());
  EXPECT_LT(m["exploration_time_s"].get<double>(), 600.0);
  EXPECT_GT(m["explored_vs_truth"]["cell_accuracy"].get<double>(), 0.85);
  EXPECT_GT(m["explored_vs_truth"]["dice_occupied"].get<double>(), 0.7);
  EXPECT_LT(m["ate_rmse_m"].get<double>(), m["odometry_ate_rmse_m"].get<double>());
  EXPECT_EQ(m["hypotheses"].get<int>(), m["targets"].get<int>());  // a request per target
  EXPECT_EQ(FirstLine(dir / "out" / "hypotheses.csv"),
            "id,t_request_s,request_scan,install_scan,end_scan,target_x_m,target_y_m,similarity,"
            "predicted_area_m2,final_similarity,best_hit_ratio,fate");
}

// With prediction off the run is the plain filter and full coverage: no P-SLAM files.
TEST(GridExplore, PredictionOffWritesNoHypotheses) {
  const fs::path dir = FreshDir("gridexplore_off");
  const auto r = RunCli("gridexplore --plan " + (kPlans / "room_with_pillar.txt").string() +
                        " --start 1.5,1.5,0 --particles 3 --max-time 20 --out " +
                        (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "hypotheses.csv"));
  const auto m = nlohmann::json::parse(ReadText(dir / "out" / "metrics.json"));
  EXPECT_FALSE(m["predict"].get<bool>());
  EXPECT_EQ(m["hypotheses"].get<int>(), 0);
}

TEST(GridExplore, BadStartsAreInputErrors) {
  const fs::path dir = FreshDir("gridexplore_bad");
  const std::string plan = " --plan " + (kPlans / "room_with_pillar.txt").string();
  const auto no_start = RunCli("gridexplore" + plan + " --out " + (dir / "a").string());
  EXPECT_EQ(no_start.exit_code, 2) << no_start.output;
  EXPECT_NE(no_start.output.find("--start"), std::string::npos) << no_start.output;
  const auto bad = RunCli("gridexplore" + plan + " --start 1,2 --out " + (dir / "b").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("x,y,theta"), std::string::npos) << bad.output;
  const auto wall =
      RunCli("gridexplore" + plan + " --start 0,3,0 --out " + (dir / "c").string());
  EXPECT_EQ(wall.exit_code, 2) << wall.output;
  EXPECT_FALSE(fs::exists(dir / "a") || fs::exists(dir / "b") || fs::exists(dir / "c"));
}

// On a real log with a deterministic schedule, prediction on gives the same run twice (bit for
// bit: the same trajectory file), and every request is listed.
TEST(GridPredict, ALogRunWithADeterministicScheduleIsReproducible) {
  const fs::path log = fs::path(SLAMKIT_DATASETS_DIR) / "carmen" / "intel.clf";
  if (!fs::exists(log)) GTEST_SKIP() << "no " << log;
  const fs::path dir = FreshDir("grid_predict");
  const std::string args = "grid --log " + log.string() +
                           " --max-scans 1500 --particles 5 --predict on "
                           "--prediction-delay-scans 3 --similarity-threshold 0.3 --out ";
  const auto a = RunCli(args + (dir / "a").string());
  const auto b = RunCli(args + (dir / "b").string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_EQ(ReadText(dir / "a" / "trajectory.txt"), ReadText(dir / "b" / "trajectory.txt"));
  EXPECT_EQ(ReadText(dir / "a" / "hypotheses.csv"), ReadText(dir / "b" / "hypotheses.csv"));
  const auto m = nlohmann::json::parse(ReadText(dir / "a" / "metrics.json"));
  EXPECT_TRUE(m["predict"].get<bool>());
  EXPECT_GT(m["hypotheses"].get<int>(), 0);
}

}  // namespace
}  // namespace slamkit
