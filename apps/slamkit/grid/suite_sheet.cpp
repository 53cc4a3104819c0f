#include "grid/suite_sheet.hpp"

#include <exception>

#include <fmt/format.h>

#include "slamkit/io/map_reader.hpp"
#include "slamkit/io/trajectory_reader.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit::app {
namespace {

namespace fs = std::filesystem;

// The panel of one run: its map and path, titled with its headline figure; a run whose outputs
// are missing or unreadable is a failed panel.
MapSheetPanel PanelOf(const SuiteRunRecord& r, const fs::path& run_dir) {
  MapSheetPanel panel;
  std::string figure;
  if (r.metrics.is_object() && r.metrics.contains("ate_rmse_m")) {
    figure = fmt::format(": ATE {:.3f} m", r.metrics["ate_rmse_m"].get<double>());
  } else if (r.metrics.is_object() && r.metrics.contains("relations_trans_mean_m")) {
    figure = fmt::format(": relations {:.3f} m", r.metrics["relations_trans_mean_m"].get<double>());
  }
  const std::string run = r.backend == "graph" ? "graph" : fmt::format("seed {}", r.seed);
  panel.title = fmt::format("{} {}{}", r.log, run, r.failure.empty() ? figure : ": failed");
  panel.failed = !r.failure.empty();
  if (panel.failed) return panel;
  try {
    panel.map = ReadOccupancyImage(run_dir / "map.yaml");
    panel.path = ReadTrajectory(run_dir / "trajectory.tum");
    panel.secondary_path = ReadTrajectory(run_dir / "odometry.tum");
  } catch (const std::exception&) {
    panel.failed = true;
  }
  return panel;
}

}  // namespace

fs::path SuiteRunDir(const fs::path& dir, const SuiteRunRecord& r) {
  return dir / "runs" / r.log / (r.backend == "graph" ? "graph" : fmt::format("seed_{}", r.seed));
}

void WriteSuiteContactSheet(const fs::path& dir, const std::vector<SuiteRunRecord>& records,
                            const std::string& title) {
  MapSheetData sheet;
  sheet.title = title;
  for (const SuiteRunRecord& r : records) sheet.panels.push_back(PanelOf(r, SuiteRunDir(dir, r)));
  WriteMapContactSheet(dir / "maps.png", sheet);
}

}  // namespace slamkit::app
