// `slamkit report DIR`: the replay viewer of a run folder, one self-contained report.html.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/commands.hpp"
#include "common/options.hpp"
#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/json_reader.hpp"
#include "slamkit/io/map_reader.hpp"
#include "slamkit/io/numeric_csv.hpp"
#include "slamkit/io/trajectory_reader.hpp"
#include "slamkit/report/html_report.hpp"

namespace slamkit::app {
namespace {

namespace fs = std::filesystem;

struct ReportOptions {
  std::string dir;
  std::string out;  // default DIR/report.html
  int max_points = static_cast<int>(HtmlReportParams{}.max_path_points);
};

// The first of `names` that the folder has.
std::optional<fs::path> First(const fs::path& dir, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (fs::exists(dir / name)) return dir / name;
  }
  return std::nullopt;
}

void AddPath(ReportData& data, const std::optional<fs::path>& file, const char* name,
             const char* color) {
  if (file) data.paths.push_back({name, color, ReadTrajectory(*file), {}});
}

// Estimated landmarks (source_id,x_m,y_m,cov_xx,cov_xy,cov_yy) or true ones (id,x_m,y_m).
void AddLandmarks(ReportData& data, const std::optional<fs::path>& file, bool estimated) {
  if (!file) return;
  const NumericCsv csv = ReadNumericCsv(*file);
  const int x = csv.Column("x_m"), y = csv.Column("y_m"), xx = csv.Column("cov_xx"),
            xy = csv.Column("cov_xy"), yy = csv.Column("cov_yy");
  if (x < 0 || y < 0) throw InputError(file->string() + ": no x_m and y_m columns");
  for (const std::vector<double>& row : csv.rows) {
    ReportLandmark l{{row[x], row[y]}, std::nullopt, estimated};
    if (xx >= 0 && xy >= 0 && yy >= 0) {
      Eigen::Matrix2d c;
      c << row[xx], row[xy], row[xy], row[yy];
      l.covariance = c;
    }
    data.landmarks.push_back(l);
  }
}

// The map history (map_history.csv: t_s,index,source_id,x_m,y_m,cov_xx,cov_xy,cov_yy), one
// snapshot per run of rows with the same t_s.
void AddMapHistory(ReportData& data, const fs::path& file) {
  const NumericCsv csv = ReadNumericCsv(file);
  const int t = csv.Column("t_s"), x = csv.Column("x_m"), y = csv.Column("y_m"),
            xx = csv.Column("cov_xx"), xy = csv.Column("cov_xy"), yy = csv.Column("cov_yy");
  if (t < 0 || x < 0 || y < 0 || xx < 0 || xy < 0 || yy < 0) {
    throw InputError(file.string() + ": not a map history (t_s,x_m,y_m,cov_xx,cov_xy,cov_yy)");
  }
  for (const std::vector<double>& row : csv.rows) {
    if (data.map_history.empty() || data.map_history.back().t_s != row[t]) {
      data.map_history.push_back({row[t], {}});
    }
    Eigen::Matrix2d c;
    c << row[xx], row[xy], row[xy], row[yy];
    data.map_history.back().landmarks.push_back({{row[x], row[y]}, c, true});
  }
}

// Each estimated pose's position covariance from pose_covariance.csv (one row per step after the
// start pose, which gets the first row's): used only when the rows pair with the poses.
void AddPoseCovariances(ReportData& data, const NumericCsv& csv) {
  const int xx = csv.Column("cov_xx"), xy = csv.Column("cov_xy"), yy = csv.Column("cov_yy");
  if (data.paths.empty() || xx < 0 || xy < 0 || yy < 0 || csv.rows.empty()) return;
  ReportPath& estimate = data.paths.front();
  if (csv.rows.size() + 1 != estimate.poses.size()) return;
  for (std::size_t i = 0; i < estimate.poses.size(); ++i) {
    const std::vector<double>& row = csv.rows[i == 0 ? 0 : i - 1];
    Eigen::Matrix2d c;
    c << row[xx], row[xy], row[xy], row[yy];
    estimate.covariances.push_back(c);
  }
}

// The column `name` of `csv` against its t_s column, as a series (empty when it has none).
void AddSeries(ReportData& data, const NumericCsv& csv, const char* column, const char* name) {
  const int t = csv.Column("t_s"), v = csv.Column(column);
  if (t < 0 || v < 0) return;
  ReportSeries s{name, {}, {}, std::nullopt};
  for (const std::vector<double>& row : csv.rows) {
    s.t_s.push_back(row[t]);
    s.values.push_back(row[v]);
  }
  data.series.push_back(std::move(s));
}

ReportData Gather(const fs::path& dir) {
  ReportData data;
  if (const auto metrics = First(dir, {"metrics.json"})) data.metrics = ReadJson(*metrics);
  AddPath(data, First(dir, {"trajectory.tum", "estimate.tum", "run_0/estimate.tum"}), "estimate",
          "#0050c8");
  AddPath(data, First(dir, {"truth.tum", "run_0/truth.tum"}), "truth", "#089000");
  AddPath(data, First(dir, {"odometry.tum"}), "odometry", "#c04040");
  if (const auto file = First(dir, {"pose_covariance.csv", "run_0/pose_covariance.csv"})) {
    AddPoseCovariances(data, ReadNumericCsv(*file));
  }
  if (const auto map = First(dir, {"map.yaml"})) data.map = ReadOccupancyImage(*map);
  AddLandmarks(data, First(dir, {"world.csv"}), false);
  AddLandmarks(data, First(dir, {"map.csv", "run_0/map.csv"}), true);
  if (const auto file = First(dir, {"map_history.csv", "run_0/map_history.csv"})) {
    AddMapHistory(data, *file);
  }
  if (const auto file = First(dir, {"consistency.csv"})) {
    const NumericCsv csv = ReadNumericCsv(*file);
    AddSeries(data, csv, "anees", "ANEES");
    // value(): a missing key must not be added to the metrics the page shows.
    const nlohmann::json band =
        data.metrics.is_object() ? data.metrics.value("anees_band", nlohmann::json()) : nullptr;
    if (!data.series.empty() && band.is_array() && band.size() == 2) {
      data.series.back().band = {band[0].get<double>(), band[1].get<double>()};
    }
    AddSeries(data, csv, "position_rmse_m", "position RMSE [m]");
    AddSeries(data, csv, "heading_rmse_rad", "heading RMSE [rad]");
  } else if (const auto errors = First(dir, {"errors.csv", "run_0/errors.csv"})) {
    const NumericCsv csv = ReadNumericCsv(*errors);
    AddSeries(data, csv, "nees", "NEES");
    AddSeries(data, csv, "error_x_m", "x error [m]");
    AddSeries(data, csv, "error_y_m", "y error [m]");
  }
  if (data.paths.empty() && !data.map && data.metrics.is_null()) {
    throw InputError(dir.string() + ": no run outputs (metrics.json, trajectory.tum, "
                     "estimate.tum, run_0/, map.yaml)");
  }
  const nlohmann::json& m = data.metrics;
  const std::string what = m.is_object() && m.contains("scenario") ? m["scenario"].get<std::string>()
                           : m.is_object() && m.contains("log")   ? m["log"].get<std::string>()
                                                                  : "";
  data.title = fmt::format("slamkit report: {}{}", fs::path(dir).filename().string(),
                           what.empty() ? "" : " (" + what + ")");
  return data;
}

int RunReportCommand(const ReportOptions& o) {
  const fs::path dir = o.dir;
  const ReportData data = Gather(dir);
  HtmlReportParams params;
  params.max_path_points = params.max_series_points = static_cast<std::size_t>(o.max_points);
  const std::string page = HtmlReport(data, params);
  const fs::path out = o.out.empty() ? dir / "report.html" : fs::path(o.out);
  WriteFileAtomically(out, [&](std::ostream& file) { file << page; });
  fmt::print("{}: {} paths, {} landmarks ({} map snapshots), {} series{}; {:.1f} MB\nwrote {}\n",
             o.dir, data.paths.size(), data.landmarks.size(), data.map_history.size(),
             data.series.size(),
             data.map ? ", the map" : "", page.size() / 1e6, out.string());
  return 0;
}

}  // namespace

void RegisterReport(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report", "a run folder as one self-contained report.html (no network): the map and the "
                "paths growing over time with a slider and a play button, landmark 2σ ellipses, "
                "error and NEES curves with a cursor, and the metrics table");
  AddExamples(cmd, {"out/intel   # after the first example of slamkit grid --help",
                    "out/default_1 --out out/default_1.html   # an mc run (slamkit mc --help)"});
  cmd->add_option("dir", o->dir, "the run folder")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--out", o->out, "the page (default DIR/report.html)");
  cmd->add_option("--max-points", o->max_points,
                  "points kept of each path and series (decimated evenly beyond)")
      ->check(CLI::Range(10, 1000000))
      ->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = RunReportCommand(*o); });
}

}  // namespace slamkit::app
