// `slamkit grid`: occupancy-grid RBPF SLAM over a CARMEN laser log.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "grid_common.hpp"
#include "progress.hpp"
#include "slamkit/runners/grid_run.hpp"
#include "slamkit/io/relations_reader.hpp"
#include "slamkit/io/writers.hpp"

namespace slamkit::app {
namespace {

struct GridOptions {
  std::string log;
  std::string relations;
  std::string out;
  bool skip_bad_lines = false;
  bool reference_from_log = false;
  bool interpolate_odometry = false;
  int max_scans = 0;
  double max_range_m = 0.0;  // 0: from the log
  RbpfGridSlamParams params;
};

int RunGridCommand(const GridOptions& o) {
  CarmenReadOptions read_options;
  read_options.skip_bad_lines = o.skip_bad_lines;
  read_options.odometry_from_scan_fields = !o.interpolate_odometry;
  if (o.max_range_m > 0.0) read_options.max_range_m = o.max_range_m;
  CarmenLog log = ReadCarmenLog(o.log, read_options);
  if (o.max_scans > 0 && static_cast<int>(log.scans.size()) > o.max_scans) {
    log.scans.resize(o.max_scans);
  }
  if (log.skipped_lines > 0) PrintStderr("{}: skipped {} bad lines\n", o.log, log.skipped_lines);
  std::vector<PoseRelation> relations;
  if (!o.relations.empty()) relations = ReadRelations(o.relations);  // fail before the long run
  OutputDir output(o.out);

  auto progress = std::make_shared<Progress>("scans", static_cast<int>(log.scans.size()));
  const GridRunResult result =
      RunGridSlam(log, o.params, [progress](int done, int) { progress->Update(done); });
  std::optional<RelationErrorStats> errors;
  if (o.max_scans > 0) relations = RelationsCovered(result.trajectory, relations);
  if (!relations.empty()) errors = EvaluateRelations(result.trajectory, relations);
  std::optional<ReferenceComparison> reference;
  if (o.reference_from_log) {
    reference = CompareWithReference(result.trajectory, LoggedTrajectory(log));
  }

  const std::filesystem::path& dir = output.staging();
  WriteGridOutputs(dir, result);
  WriteJson(dir / "metrics.json",
            GridMetrics(result, o.params, errors ? &*errors : nullptr,
                        reference ? &*reference : nullptr, PeakRssMib()));

  PrintGridRun(o.log, result, o.params.particles);
  if (errors) {
    fmt::print("  {:<28}{:>12}\n", "relations: translation [m]",
               fmt::format("{:.4f} ± {:.4f}", errors->trans_mean_m, errors->trans_std_m));
    fmt::print("  {:<28}{:>12}\n", "relations: rotation [deg]",
               fmt::format("{:.3f} ± {:.3f}", errors->rot_mean_deg, errors->rot_std_deg));
  }
  output.Commit();
  if (reference) PrintComparison("log poses", *reference);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

}  // namespace

void RegisterGrid(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<GridOptions>();
  CLI::App* cmd = app.add_subcommand("grid", "occupancy-grid RBPF SLAM on a CARMEN laser log");
  cmd->add_option("--log", o->log, "CARMEN log (.clf/.log, optionally gzip-compressed)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_option("--relations", o->relations, "relations file (Kümmerle et al. 2009)")
      ->check(CLI::ExistingFile);
  AddGridFilterOptions(cmd, o->params);
  cmd->add_option("--max-map-extent", o->params.grid.max_extent_m,
                  "largest |x| or |y| the map may reach [m]")->check(CLI::PositiveNumber);
  cmd->add_option("--max-map-cells", o->params.grid.max_cells,
                  "largest map area in cells (1 byte each)")->check(CLI::PositiveNumber);
  cmd->add_flag("--skip-bad-lines", o->skip_bad_lines, "skip malformed log lines (counted)");
  cmd->add_option("--max-scans", o->max_scans, "use only the first N scans (0: all)")
      ->check(NonNegativeNumber());
  cmd->add_option("--max-range", o->max_range_m,
                  "the laser's no-return range [m]: a reading at or above it is no return "
                  "(default: the log's PARAM, else its largest reading)")
      ->check(PositiveNumber());
  cmd->add_flag("--interpolate-odometry", o->interpolate_odometry,
                "odometry at each scan interpolated from the ODOM records at the scan's time, "
                "instead of the scan record's own odometry fields");
  cmd->add_flag("--reference-from-log", o->reference_from_log,
                "compare with the poses the log gives (corrected logs): ATE and RPE");
  cmd->callback([o, &exit_code] {
    exit_code = RunGridCommand(*o);
  });
}

}  // namespace slamkit::app
