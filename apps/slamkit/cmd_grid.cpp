// `slamkit grid`: occupancy-grid RBPF SLAM over a CARMEN laser log.
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "commands.hpp"
#include "grid_common.hpp"
#include "progress.hpp"
#include "slamkit/runners/grid_run.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/relations_reader.hpp"
#include "slamkit/io/trajectory_reader.hpp"
#include "slamkit/runners/grid_config.hpp"
#include "slamkit/io/writers.hpp"

namespace slamkit::app {
namespace {

struct GridOptions {
  std::string log;
  std::string config;
  std::string relations;
  std::string reference;
  PairBy pair_by = PairBy::kTime;
  std::string out;
  bool skip_bad_lines = false;
  bool reference_from_log = false;
  bool interpolate_odometry = false;
  int max_scans = 0;
  int threads = 0;           // 0: the CPUs this process may use
  bool frame_odometry = false;
  bool seed_given = false;       // --seed and --particles override --config
  bool particles_given = false;  // keep the log's odometry frame instead of starting at the origin
  double max_range_m = 0.0;  // 0: from the log
  RbpfGridSlamParams params;
};

// The reference poses to compare with, checked before the long run: read from --reference, or
// the log's own (--reference-from-log); nullopt without either.
std::optional<Trajectory> LoadReference(const GridOptions& o, const CarmenLog& log) {
  if (o.reference_from_log) {
    bool odometry_is_pose = !log.scans.empty();
    for (const LaserScan& scan : log.scans) {
      odometry_is_pose = odometry_is_pose &&
                         (scan.odometry.vector() - scan.logged_pose.vector()).norm() < 1e-9;
    }
    if (odometry_is_pose) {
      PrintStderr("warning: {}: every scan's odometry equals its logged pose, so the filter is "
                  "given the reference as its odometry and this comparison measures nothing\n",
                  o.log);
    }
    return LoggedTrajectory(log);
  }
  if (o.reference.empty()) return std::nullopt;
  Trajectory reference = ReadTrajectory(o.reference);
  if (o.pair_by == PairBy::kIndex) {
    if (o.max_scans > 0 && reference.size() > log.scans.size()) reference.resize(log.scans.size());
    if (reference.size() != log.scans.size()) {
      throw InputError(fmt::format("{}: {} poses for the {} scans of {} (--pair-by index pairs "
                                   "pose i with scan i)",
                                   o.reference, reference.size(), log.scans.size(), o.log));
    }
  } else if (const std::string problem = TimestampProblem(reference); !problem.empty()) {
    throw InputError(fmt::format("{}: its timestamps cannot pair poses ({}): use --pair-by index",
                                 o.reference, problem));
  }
  return reference;
}

// The evaluations after the run. A failing one is reported and recorded, never allowed to lose
// the run's outputs.
struct GridEvaluation {
  std::optional<RelationErrorStats> relations;
  std::optional<ReferenceComparison> reference;
  // The same for the log's raw odometry: the baseline the estimate must beat.
  std::optional<RelationErrorStats> odometry_relations;
  std::optional<ReferenceComparison> odometry_reference;
  std::string error;
};

GridEvaluation Evaluate(const GridOptions& o, const GridRunResult& result,
                        const Trajectory& odometry, std::vector<PoseRelation> relations,
                        const std::optional<Trajectory>& reference) {
  GridEvaluation e;
  try {
    if (o.max_scans > 0) relations = RelationsCovered(result.trajectory, relations);
    if (!relations.empty()) {
      e.relations = EvaluateRelations(result.trajectory, relations);
      e.odometry_relations = EvaluateRelations(odometry, relations);
    }
    if (reference) {
      const PairBy pair_by = o.reference_from_log ? PairBy::kIndex : o.pair_by;
      e.reference = CompareWithReference(result.trajectory, *reference, pair_by);
      e.odometry_reference = CompareWithReference(odometry, *reference, pair_by);
    }
  } catch (const std::exception& ex) {
    e.error = ex.what();
  }
  return e;
}

void AddOdometryMetrics(const GridEvaluation& e, nlohmann::json& metrics) {
  if (e.odometry_relations) {
    metrics["odometry_relations_trans_mean_m"] = e.odometry_relations->trans_mean_m;
    metrics["odometry_relations_rot_mean_deg"] = e.odometry_relations->rot_mean_deg;
  }
  if (e.odometry_reference) {
    metrics["odometry_ate_rmse_m"] = e.odometry_reference->ate.rmse_m;
    metrics["odometry_rpe_trans_mean_m"] = e.odometry_reference->rpe.trans_mean_m;
    metrics["odometry_rpe_rot_mean_deg"] = e.odometry_reference->rpe.rot_mean_deg;
  }
}

CarmenLog ReadGridLog(const GridOptions& o) {
  CarmenReadOptions read_options;
  read_options.skip_bad_lines = o.skip_bad_lines;
  read_options.odometry_from_scan_fields = !o.interpolate_odometry;
  if (o.max_range_m > 0.0) read_options.max_range_m = o.max_range_m;
  CarmenLog log = ReadCarmenLog(o.log, read_options);
  if (o.max_scans > 0 && static_cast<int>(log.scans.size()) > o.max_scans) {
    log.scans.resize(o.max_scans);
  }
  if (log.skipped_lines > 0) PrintStderr("{}: skipped {} bad lines\n", o.log, log.skipped_lines);
  for (const std::string& note : log.notes) PrintStderr("{}: {}\n", o.log, note);
  return log;
}

// The filter's parameters (the options, or --config with --seed and --particles over it), and
// the frame: the log's odometry frame with --frame odometry, else `odometry` is moved to start at
// the origin, where the filter starts.
RbpfGridSlamParams EffectiveParams(const GridOptions& o, Trajectory* odometry) {
  RbpfGridSlamParams params = o.params;
  if (!o.config.empty()) {
    params = LoadGridConfig(o.config);
    if (o.seed_given) params.seed = o.params.seed;
    if (o.particles_given) params.particles = o.params.particles;
  }
  if (o.frame_odometry) {
    params.initial_pose = odometry->front().pose;
  } else {
    const Pose2 to_origin = odometry->front().pose.Inverse();
    for (StampedPose& p : *odometry) p.pose = to_origin.Compose(p.pose);
  }
  return params;
}

nlohmann::json RunMetrics(const GridOptions& o, const CarmenLog& log, const GridRunResult& result,
                          const RbpfGridSlamParams& params, const GridEvaluation& eval) {
  nlohmann::json metrics =
      GridMetrics(result, params, eval.relations ? &*eval.relations : nullptr,
                  eval.reference ? &*eval.reference : nullptr, PeakRssMib());
  if (!o.reference.empty()) {
    metrics["reference"] = o.reference;
    metrics["pair_by"] = o.pair_by == PairBy::kIndex ? "index" : "time";
  }
  metrics["log"] = o.log;
  metrics["version"] = SLAMKIT_VERSION;
  metrics["params"] = GridParamsJson(params);
  if (!o.config.empty()) metrics["config"] = o.config;
  metrics["skipped_lines"] = log.skipped_lines;
  metrics["no_return_beams"] = log.no_return_beams;
  metrics["reader_notes"] = log.notes;
  AddOdometryMetrics(eval, metrics);
  if (!eval.error.empty()) metrics["evaluation_error"] = eval.error;
  return metrics;
}

void PrintRelations(const RelationErrorStats& r) {
  fmt::print("  {:<28}{:>12}\n", "relations: translation [m]",
             fmt::format("{:.4f} ± {:.4f}", r.trans_mean_m, r.trans_std_m));
  fmt::print("  {:<28}{:>12}\n", "relations: rotation [deg]",
             fmt::format("{:.3f} ± {:.3f}", r.rot_mean_deg, r.rot_std_deg));
  if (r.skipped > 0) {
    PrintStderr("warning: {} relations lie outside the run's time span and were skipped\n",
                r.skipped);
  }
}

int RunGridCommand(const GridOptions& o) {
  // Every parallel loop of the filter runs in TBB's pool, which this caps.
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(o.threads > 0 ? o.threads
                                                                           : UsableCpuCount()));
  const CarmenLog log = ReadGridLog(o);
  std::vector<PoseRelation> relations;
  if (!o.relations.empty()) relations = ReadRelations(o.relations);  // fail before the long run
  const std::optional<Trajectory> reference = LoadReference(o, log);
  Trajectory odometry = OdometryTrajectory(log);
  const RbpfGridSlamParams params = EffectiveParams(o, &odometry);
  OutputDir output(o.out);

  auto progress = std::make_shared<Progress>("scans", static_cast<int>(log.scans.size()));
  const GridRunResult result =
      RunGridSlam(log, params, [progress](int done, int) { progress->Update(done); });
  const GridEvaluation eval = Evaluate(o, result, odometry, std::move(relations), reference);

  const std::filesystem::path& dir = output.staging();
  const std::string title = std::filesystem::path(o.log).filename().string();
  if (const int moved = WriteGridOutputs(dir, result, odometry, title); moved > 0) {
    PrintStderr("warning: {}: its scan timestamps cannot pair poses ({}): pair by index; "
                "trajectory.tum's {} such times were pushed forward in 1 µs steps for TUM "
                "readers, trajectory.txt keeps the log's\n",
                o.log, TimestampProblem(result.trajectory), moved);
  }
  WriteJson(dir / "metrics.json", RunMetrics(o, log, result, params, eval));
  PrintGridRun(o.log, result, params.particles);
  if (eval.relations) PrintRelations(*eval.relations);
  output.Commit();
  if (eval.reference) {
    PrintComparison(o.reference_from_log ? "log poses" : "reference", *eval.reference);
  }
  fmt::print("wrote {}\n", o.out);
  if (!eval.error.empty()) {
    PrintStderr("error: the evaluation failed ({}); the run's outputs are kept in {}\n",
                eval.error, o.out);
    return 1;
  }
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
  const std::vector<CLI::Option*> filter_options = AddGridFilterOptions(cmd, o->params);
  CLI::Option* config =
      cmd->add_option("--config", o->config,
                      "the filter's parameters from a YAML file (configs/grid.yaml); instead of "
                      "the filter options, but --seed and --particles override it")
          ->check(CLI::ExistingFile);
  for (CLI::Option* option : filter_options) {
    if (option->get_name() != "--seed" && option->get_name() != "--particles") {
      config->excludes(option);
    }
  }
  cmd->add_option("--max-map-extent", o->params.grid.max_extent_m,
                  "largest |x| or |y| the map may reach [m]")->check(CLI::PositiveNumber);
  cmd->add_option("--max-map-cells", o->params.grid.max_cells,
                  "largest map area in cells (1 byte each)")->check(CLI::PositiveNumber);
  cmd->add_option("--frame", o->frame_odometry,
                  "origin: the first scan at (0, 0, 0); odometry: the log's odometry frame")
      ->transform(CLI::CheckedTransformer(std::map<std::string, bool>{{"origin", false},
                                                                      {"odometry", true}}))
      ->default_str("origin");
  cmd->add_option("--threads", o->threads, "worker threads (0: all the CPUs this process may use)")
      ->check(CLI::Range(0, 1024));
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
  cmd->add_option("--reference", o->reference,
                  "reference poses, one per line: `t x y theta` or TUM; ATE and RPE against them")
      ->check(CLI::ExistingFile);
  cmd->add_option("--pair-by", o->pair_by,
                  "pair --reference poses with scans by timestamp (time) or by order (index)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, PairBy>{{"time", PairBy::kTime}, {"index", PairBy::kIndex}}))
      ->default_str("time");
  cmd->add_flag("--reference-from-log", o->reference_from_log,
                "compare with the poses the log gives (corrected logs): ATE and RPE, by index")
      ->excludes("--reference");
  cmd->callback([o, cmd, &exit_code] {
    o->seed_given = cmd->count("--seed") > 0;
    o->particles_given = cmd->count("--particles") > 0;
    exit_code = RunGridCommand(*o);
  });
}

}  // namespace slamkit::app
