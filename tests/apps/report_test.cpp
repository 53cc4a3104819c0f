// `slamkit report DIR` (issue 31 part 2): the page of an mc run and of a grid run, loaded from
// disk in headless Chromium (Debian's `chromium`): its metrics equal metrics.json, the slider
// moves the path, and the screenshots are drawn, not blank.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

constexpr const char* kChromium = "/usr/bin/chromium";

// Chromium headless on the page at `fraction` of the slider: the DOM after the script ran
// (`screenshot` empty) or a screenshot into `screenshot`.
std::string Chromium(const fs::path& page, double fraction, const fs::path& screenshot = {}) {
  const std::string url = "file://" + fs::absolute(page).string() + "#t=" + std::to_string(fraction);
  const std::string action = screenshot.empty() ? "--dump-dom"
                                                : "--screenshot=" + screenshot.string() +
                                                      " --window-size=1400,1000";
  const std::string command = std::string(kChromium) +
                              " --headless=new --no-sandbox --disable-gpu --hide-scrollbars "
                              "--user-data-dir=" + (page.parent_path() / "chromium").string() +
                              " --virtual-time-budget=4000 " + action + " '" + url + "' 2>/dev/null";
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  pclose(pipe);
  return out;
}

// The text of the element with id `id` in `dom`.
std::string ElementText(const std::string& dom, const std::string& id) {
  const std::regex element("id=\"" + id + "\"[^>]*>([^<]*)<");
  std::smatch match;
  return std::regex_search(dom, match, element) ? match[1].str() : std::string("(missing)");
}

class Report : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kChromium)) GTEST_SKIP() << "no chromium (scripts/setup.sh installs it)";
    dir_ = FreshDir(std::string("report_") +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  fs::path dir_;
};

TEST_F(Report, TheMonteCarloPageShowsTheMetricsAndMovesWithTheSlider) {
  const fs::path run = dir_ / "mc";
  ASSERT_EQ(RunCli("mc --config " + std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml "
                   "--runs 3 --no-figures --out " + run.string()).exit_code, 0);
  const CliResult r = RunCli("report " + run.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path page = run / "report.html";
  const std::string html = ReadText(page);
  // Self-contained: nothing fetched from anywhere.
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_LT(html.size(), 20u << 20);
  const auto metrics = nlohmann::json::parse(std::ifstream(run / "metrics.json"));
  const std::string dom = Chromium(page, 0.25);
  ASSERT_NE(dom.find("data-drawn=\"250\""), std::string::npos) << dom.substr(0, 2000);
  for (const char* key : {"anees", "position_rmse_m", "heading_rmse_rad", "runs"}) {
    EXPECT_EQ(std::stod(ElementText(dom, std::string("m-") + key)), metrics[key].get<double>())
        << key;
  }
  EXPECT_EQ(std::stod(ElementText(dom, "m-association.sightings")),
            metrics["association"]["sightings"].get<double>());
  // A quarter of the way the path has a quarter of its poses.
  const std::string time = ElementText(dom, "time");
  const std::smatch counts = [&] {
    std::smatch m;
    std::regex_search(time, m, std::regex(R"(\((\d+)/(\d+)\))"));
    return m;
  }();
  ASSERT_EQ(counts.size(), 3u) << time;
  EXPECT_NEAR(std::stod(counts[1]) / std::stod(counts[2]), 0.25, 0.01) << time;
  // The pose's 2σ ellipse at that time: the filter's covariance after that step
  // (run_0/pose_covariance.csv; pose k comes after step k, the start before step 1).
  const int pose = std::stoi(counts[1]) - 1;
  std::istringstream rows(ReadText(run / "run_0" / "pose_covariance.csv"));
  std::string row;
  for (int i = 0; i <= pose && std::getline(rows, row);) ++i;  // header, then rows 1 .. pose
  double t = 0, xx = 0, xy = 0, xt = 0, yy = 0;
  char comma = 0;
  std::istringstream(row) >> t >> comma >> xx >> comma >> xy >> comma >> xt >> comma >> yy;
  const double major = 2.0 * std::sqrt(0.5 * (xx + yy) + std::hypot(0.5 * (xx - yy), xy));
  const std::string sigma = ElementText(dom, "pose-sigma");
  ASSERT_NE(sigma.find("pose 2σ ellipse "), std::string::npos) << sigma;
  EXPECT_NEAR(std::stod(sigma.substr(sigma.find("ellipse ") + 8)), major, 0.005 * major) << sigma;
  // The landmarks drawn at that time are the map history's last snapshot at or before it
  // (run_0/map_history.csv, t_s first), fewer than the final map's.
  std::istringstream poses(ReadText(run / "run_0" / "estimate.tum"));
  for (int i = 0; i <= pose && std::getline(poses, row);) {
    if (!row.empty() && row[0] != '#') ++i;
  }
  const double pose_t = std::stod(row);
  std::istringstream history(ReadText(run / "run_0" / "map_history.csv"));
  std::getline(history, row);  // header
  double snapshot_t = -1;
  int in_snapshot = 0;
  while (std::getline(history, row)) {
    const double row_t = std::stod(row);
    if (row_t > pose_t) break;
    in_snapshot = row_t == snapshot_t ? in_snapshot + 1 : 1;
    snapshot_t = row_t;
  }
  ASSERT_GT(in_snapshot, 0);
  EXPECT_EQ(ElementText(dom, "landmarks-shown"),
            std::to_string(in_snapshot) + " estimated landmarks");
  const std::string final_count = ElementText(Chromium(page, 1.0), "landmarks-shown");
  EXPECT_LT(in_snapshot, std::stoi(final_count)) << final_count;
  // Drawn: a screenshot at a quarter and one at the end differ, and neither is blank (a blank
  // 1400 x 1000 page compresses to a few kB).
  const fs::path early = dir_ / "early.png", late = dir_ / "late.png";
  Chromium(page, 0.25, early);
  Chromium(page, 1.0, late);
  ASSERT_TRUE(fs::exists(early) && fs::exists(late));
  EXPECT_GT(fs::file_size(early), 30000u);
  EXPECT_NE(ReadText(early), ReadText(late));
}

TEST_F(Report, TheGridPageCarriesItsMapAndAMissingRunIsAnError) {
  const fs::path run = dir_ / "grid";
  const std::string carmen = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/";
  if (!fs::exists(carmen + "intel.clf")) GTEST_SKIP() << "no intel.clf";
  ASSERT_EQ(RunCli("grid --log " + carmen + "intel.clf --max-scans 400 --relations " + carmen +
                   "intel.relations --out " + run.string()).exit_code, 0);
  ASSERT_EQ(RunCli("report " + run.string() + " --out " + (dir_ / "grid.html").string()).exit_code,
            0);
  const std::string html = ReadText(dir_ / "grid.html");
  EXPECT_NE(html.find("\"map\":{"), std::string::npos);
  const std::string dom = Chromium(dir_ / "grid.html", 1.0);
  const auto metrics = nlohmann::json::parse(std::ifstream(run / "metrics.json"));
  EXPECT_EQ(std::stod(ElementText(dom, "m-relations_trans_mean_m")),
            metrics["relations_trans_mean_m"].get<double>());
  EXPECT_NE(ElementText(dom, "time").find("(400/400)"), std::string::npos);
  fs::create_directories(dir_ / "empty");
  const CliResult empty = RunCli("report " + (dir_ / "empty").string());
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.output.find("no run outputs"), std::string::npos) << empty.output;
  EXPECT_FALSE(fs::exists(dir_ / "empty" / "report.html"));
}

}  // namespace
}  // namespace slamkit::testing
