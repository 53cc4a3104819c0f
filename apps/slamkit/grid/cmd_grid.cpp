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

#include "common/commands.hpp"
#include "grid/grid_outputs.hpp"
#include "common/log_input.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/grid/grid_config.hpp"
#include "slamkit/runners/grid/grid_run.hpp"

namespace slamkit::app {
namespace {

struct GridOptions {
  LogInput input;
  std::string config;
  std::string out;
  int threads = 0;               // 0: the CPUs this process may use
  bool frame_odometry = false;   // keep the log's odometry frame instead of starting at the origin
  bool seed_given = false;       // --seed and --particles override --config
  bool particles_given = false;
  bool backend_given = false;
  GridSlamConfig slam;  // the filter options' values
  std::string predict = "off";
  std::string recovery = "on";
  GridPredictionConfig prediction;
};

// P-SLAM's keys in metrics.json, when it ran.
void AddPredictionMetrics(const PredictiveRunResult& r, const GridPredictionConfig& p,
                          nlohmann::json& metrics) {
  metrics["predict"] = true;
  metrics["recovery"] = p.prediction.recovery;
  metrics["similarity_threshold"] = p.predictor.similarity_threshold;
  metrics["prediction_delay_scans"] = p.prediction.deterministic_delay_scans;
  metrics["hypotheses"] = r.hypotheses.size();
  metrics["hypotheses_by_fate"] = HypothesisFateCounts(r.hypotheses);
  long cells = 0;
  ForEachKnownCell(r.predicted, [&](const CellIndex&, OccupancyGrid::CellValue) { ++cells; });
  metrics["predicted_area_m2"] = cells * r.predicted.resolution() * r.predicted.resolution();
}

// The filter's parameters (the options, or --config with --seed and --particles over it), and
// the frame: the log's odometry frame with --frame odometry, else `odometry` is moved to start at
// the origin, where the filter starts.
GridSlamConfig EffectiveParams(const GridOptions& o, Trajectory* odometry) {
  GridSlamConfig params = o.slam;
  if (!o.config.empty()) {
    params = LoadGridConfig(o.config);
    if (o.seed_given) params.rbpf.seed = o.slam.rbpf.seed;
    if (o.particles_given) params.rbpf.particles = o.slam.rbpf.particles;
    if (o.backend_given) params.backend = o.slam.backend;
  }
  if (o.frame_odometry) {
    params.rbpf.initial_pose = odometry->front().pose;
  } else {
    const Pose2 to_origin = odometry->front().pose.Inverse();
    for (StampedPose& p : *odometry) p.pose = to_origin.Compose(p.pose);
  }
  return params;
}

nlohmann::json RunMetrics(const GridOptions& o, const CarmenLog& log, const GridRunResult& result,
                          const GridSlamConfig& params, const LogEvaluation& eval) {
  nlohmann::json metrics =
      GridMetrics(result, params, eval.relations ? &*eval.relations : nullptr,
                  eval.reference ? &*eval.reference : nullptr, PeakRssMib());
  metrics["version"] = SLAMKIT_VERSION;
  metrics["params"] = GridParamsJson(params);
  if (!o.config.empty()) metrics["config"] = o.config;
  AddLogInputMetrics(o.input, log, eval, metrics);
  return metrics;
}

int RunGridCommand(const GridOptions& o) {
  // Every parallel loop of the filter runs in TBB's pool, which this caps.
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(o.threads > 0 ? o.threads
                                                                           : UsableCpuCount()));
  const CarmenLog log = ReadInputLog(o.input);
  std::vector<PoseRelation> relations = ReadInputRelations(o.input);  // fail before the long run
  const std::optional<Trajectory> reference = LoadReference(o.input, log);
  Trajectory odometry = OdometryTrajectory(log);
  const GridSlamConfig params = EffectiveParams(o, &odometry);
  if (o.predict == "on" && params.backend != GridBackend::kRbpf) {
    throw InputError("grid: --predict on needs the rbpf back end (P-SLAM weighs particles)");
  }
  OutputDir output(o.out);

  auto progress = std::make_shared<Progress>("scans", static_cast<int>(log.scans.size()));
  const auto report = [progress](int done, int) { progress->Update(done); };
  std::optional<PredictiveRunResult> predictive;
  if (o.predict == "on") predictive = RunPredictiveGridSlam(log, params, o.prediction, report);
  const GridRunResult result = predictive ? predictive->run : RunGridSlam(log, params, report);
  const LogEvaluation eval =
      EvaluateOnLog(result.trajectory, odometry, std::move(relations), reference,
                    ScoringOf(o.input));

  const std::filesystem::path& dir = output.staging();
  const std::string title = std::filesystem::path(o.input.source()).filename().string();
  if (const int moved = WriteGridOutputs(dir, result, odometry, title); moved > 0) {
    PrintStderr("warning: {}: its scan timestamps cannot pair poses ({}): pair by index; "
                "trajectory.tum's {} such times were pushed forward in 1 µs steps for TUM "
                "readers, trajectory.txt keeps the log's\n",
                o.input.source(), TimestampProblem(result.trajectory), moved);
  }
  nlohmann::json metrics = RunMetrics(o, log, result, params, eval);
  if (predictive) {
    AddPredictionMetrics(*predictive, o.prediction, metrics);
    WritePredictionOutputs(dir, result, predictive->hypotheses, predictive->predicted);
  }
  WriteJson(dir / "metrics.json", metrics);
  PrintGridRun(o.input.source(), result, params.rbpf.particles);
  if (eval.relations) PrintRelations(*eval.relations);
  output.Commit();
  return ReportEvaluation(o.input, eval, o.out);
}

}  // namespace

void RegisterGrid(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<GridOptions>();
  CLI::App* cmd = app.add_subcommand("grid", "occupancy-grid SLAM on a CARMEN laser log (--backend rbpf: particle filter; graph: submaps and a pose graph)");
  AddExamples(cmd, {
               "--log ../shared/datasets/carmen/intel.clf --relations ../shared/datasets/carmen/intel.relations --out out/intel",
               "--log ../shared/datasets/carmen/intel.clf --relations ../shared/datasets/carmen/intel.relations --backend graph --out out/intel_graph"});
  AddLogInputOptions(cmd, o->input);
  cmd->add_option("--out", o->out, "output directory")->required();
  const std::vector<CLI::Option*> filter_options = AddGridFilterOptions(cmd, o->slam);
  CLI::Option* config =
      cmd->add_option("--config", o->config,
                      "the filter's parameters from a YAML file (configs/grid.yaml); instead of "
                      "the filter options, but --backend, --seed and --particles override it")
          ->check(CLI::ExistingFile);
  for (CLI::Option* option : filter_options) {
    const std::string name = option->get_name();
    if (name != "--seed" && name != "--particles" && name != "--backend") {
      config->excludes(option);
    }
  }
  cmd->add_option("--max-map-extent", o->slam.rbpf.grid.max_extent_m,
                  "largest |x| or |y| the map may reach [m]")->check(CLI::PositiveNumber);
  cmd->add_option("--max-map-cells", o->slam.rbpf.grid.max_cells,
                  "largest map area in cells (1 byte each)")->check(CLI::PositiveNumber);
  cmd->add_option("--frame", o->frame_odometry,
                  "origin: the first scan at (0, 0, 0); odometry: the log's odometry frame")
      ->transform(CLI::CheckedTransformer(std::map<std::string, bool>{{"origin", false},
                                                                      {"odometry", true}}))
      ->default_str("origin");
  cmd->add_option("--threads", o->threads, "worker threads (0: all the CPUs this process may use)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--predict", o->predict,
                  "P-SLAM's structure prediction (SPEC S4): hypotheses.csv, predicted.pgm, "
                  "map_predicted.png")->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  cmd->add_option("--recovery", o->recovery, "with --predict on: drop predictions the scans do "
                  "not support (Eq. 23)")->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  cmd->add_option("--similarity-threshold", o->prediction.predictor.similarity_threshold,
                  "with --predict on: least Psi (Eq. 5) for a hypothesis")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--region-diameter", o->prediction.predictor.region_diameter_m,
                  "d: the prediction compares and fills the disc of this diameter around the "
                  "target [m]")->check(CLI::Range(1.0, 100.0))->capture_default_str();
  cmd->add_option("--prediction-delay-scans", o->prediction.prediction.deterministic_delay_scans,
                  "with --predict on: take each prediction exactly N scans after its request "
                  "(0: as soon as the thread has it; not reproducible bit for bit)")
      ->check(CLI::Range(0, 100000))->capture_default_str();
  cmd->callback([o, cmd, &exit_code] {
    o->prediction.predict = o->predict == "on";
    o->prediction.prediction.recovery = o->recovery == "on";
    o->seed_given = cmd->count("--seed") > 0;
    o->particles_given = cmd->count("--particles") > 0;
    o->backend_given = cmd->count("--backend") > 0;
    exit_code = RunGridCommand(*o);
  });
}

}  // namespace slamkit::app
