#include "grid/grid_outputs.hpp"

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <fstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "common/options.hpp"
#include "slamkit/io/grid_writers.hpp"
#include "slamkit/io/pose_graph_io.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/grid/grid_config.hpp"

namespace slamkit::app {

std::vector<CLI::Option*> AddGridFilterOptions(CLI::App* cmd, GridSlamConfig& config) {
  std::vector<CLI::Option*> options = AddParamOptions(cmd, GridParamTable(config));
  RbpfGridSlamParams& p = config.rbpf;
  options.push_back(cmd->add_flag_callback(
      "--match-proposal", [&p] { p.proposal = ProposalScheme::kScanMatch; },
      "take each particle's scan match as its pose (ROS GMapping) instead of drawing from the "
      "Gaussian fitted around it (Grisetti et al. 2007)"));
  // Either order of the two flags gives the same mode: --no-tracking wins.
  options.push_back(cmd->add_flag_callback(
      "--odometry-motion",
      [&p] {
        if (p.tracking_mode == TrackingMode::kTrackedMotion) {
          p.tracking_mode = TrackingMode::kTrackOnly;
        }
      },
      "move the particles by raw odometry between updates, not by the tracked motion"));
  options.push_back(cmd->add_flag_callback(
      "--no-tracking", [&p] { p.tracking_mode = TrackingMode::kOff; },
      "poses of scans between updates by odometry alone (as GMapping), not tracked against the "
      "best map; the particles then move by odometry too"));
  return options;
}

int WriteGridOutputs(const std::filesystem::path& dir, const GridRunResult& result,
                     const Trajectory& odometry, const std::string& title) {
  std::filesystem::create_directories(dir);
  WritePoseText(dir / "trajectory.txt", result.trajectory);
  int moved = 0;
  WriteTumTrajectory(dir / "trajectory.tum", WithIncreasingTimes(result.trajectory, 1e-6, &moved));
  if (!odometry.empty()) WriteTumTrajectory(dir / "odometry.tum", WithIncreasingTimes(odometry));
  WriteOccupancyGridPgm(dir / "map.pgm", result.map);
  if (result.graph) WritePoseGraphG2o(dir / "graph.g2o", result.pose_graph);
  // map.png is the figure (cropped, the paths over it, a scale bar); map.pgm holds every cell.
#ifdef __GLIBC__
  // The filter's particles and maps are gone by now, but glibc keeps their freed pages; handing
  // them back first keeps the figure's canvas from adding to the peak (Intel: 145 -> 116 MiB).
  malloc_trim(0);
#endif
  MapSheetData figure;
  figure.columns = 1;
  figure.panel_px = 1200;
  figure.panels.push_back({title, RenderOccupancyImage(result.map), result.trajectory, odometry});
  WriteMapContactSheet(dir / "map.png", figure);
  return moved;
}

namespace {

void WriteHypothesesCsv(const std::filesystem::path& path, const std::vector<HypothesisRow>& rows) {
  std::ofstream out(path);
  out << "id,t_request_s,request_scan,install_scan,end_scan,target_x_m,target_y_m,similarity,"
         "predicted_area_m2,final_similarity,best_hit_ratio,fate\n";
  for (const HypothesisRow& row : rows) {
    const HypothesisRecord& r = row.record;
    const GridHypothesis& h = r.hypothesis;
    out << fmt::format("{},{:.3f},{},{},{},{:.2f},{:.2f},{:.4f},{:.2f},{},{},{}\n", h.id, h.t_s,
                       r.request_scan, r.install_scan, r.end_scan, h.target_m.x(),
                       h.target_m.y(), h.similarity, h.area_m2(),
                       row.final_similarity ? fmt::format("{:.4f}", *row.final_similarity) : "",
                       r.best_hit_ratio >= 0.0 ? fmt::format("{:.4f}", r.best_hit_ratio) : "",
                       HypothesisFateName(r.fate));
  }
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

void WritePredictionOutputs(const std::filesystem::path& dir, const GridRunResult& result,
                            const std::vector<HypothesisRow>& hypotheses,
                            const OccupancyGrid& predicted) {
  WriteHypothesesCsv(dir / "hypotheses.csv", hypotheses);
  WriteOccupancyGridPgm(dir / "predicted.pgm", predicted);
  MapSheetData sheet;
  sheet.panel_px = 900;
  MapSheetPanel panel{"explored (grey) and predicted (orange)", RenderOccupancyImage(result.map),
                      result.trajectory, {}, false};
  if (predicted.min_cell().x <= predicted.max_cell().x) {
    panel.overlay = RenderOccupancyImage(predicted);
  }
  sheet.panels.push_back(std::move(panel));
  WriteMapContactSheet(dir / "map_predicted.png", sheet);
}

void PrintGridRun(const std::string& source, const GridRunResult& result, int particles) {
  if (result.graph) {
    const GraphSlamStats& g = *result.graph;
    fmt::print("{}: {} scans, {} nodes, {} submaps, {} loop closures ({} disagreeing)\n", source,
               result.scans, g.nodes, g.submaps, g.loop_closures, g.loop_closures_disagreeing);
    fmt::print("  front end: {} matches rescued, {} left to odometry\n", g.matches_rescued,
               g.matches_kept_odometry);
  } else {
    fmt::print("{}: {} scans, {} updates, {} resamples, {} particles\n", source, result.scans,
               result.updates, result.resamples, particles);
  }
  fmt::print("  {:<28}{:>12.2f}\n", "wall time [s]", result.wall_time_s);
  fmt::print("  {:<28}{:>12.1f}\n", "scans per second", result.scans / result.wall_time_s);
  fmt::print("  {:<28}{:>12.1f}\n", "peak memory [MiB]", PeakRssMib());
  PrintHeadingDrift(result.odometry_heading_drift);
  if (result.heading_drift_in_use_rad_per_m != 0.0) {
    fmt::print("  {:<28}{:>12.5f}\n", "drift applied at the end",
               result.heading_drift_in_use_rad_per_m);
  }
}

void PrintHeadingDrift(const std::optional<HeadingDriftFit>& fit) {
  if (!fit) return;
  fmt::print("  {:<28}{:>12.5f}  (rms turn error per window {:.3f} -> {:.3f} rad)\n",
             "odometry drift [rad/m]", fit->drift_rad_per_m, fit->rms_before_rad,
             fit->rms_after_rad);
}

void PrintComparison(const std::string& against, const ReferenceComparison& c) {
  fmt::print("  {:<28}{:>12}\n", fmt::format("ATE vs {} [m]", against),
             fmt::format("{:.4f} rms, {:.4f} max", c.ate.rmse_m, c.ate.max_m));
  fmt::print("  {:<28}{:>12}\n", "RPE translation [m]",
             fmt::format("{:.4f} ± {:.4f}", c.rpe.trans_mean_m, c.rpe.trans_std_m));
  fmt::print("  {:<28}{:>12}\n", "RPE rotation [deg]",
             fmt::format("{:.3f} ± {:.3f}", c.rpe.rot_mean_deg, c.rpe.rot_std_deg));
}

}  // namespace slamkit::app
