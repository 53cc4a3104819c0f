// `slamkit posegraph FILE --out DIR`: a g2o or TORO pose graph optimised (issue 30).
#include <memory>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/pose_graph_io.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/graph/posegraph_run.hpp"

namespace slamkit::app {
namespace {

struct PoseGraphOptions {
  std::string file;
  std::string out;
  std::string objective = "chi2";
  std::string start = "both";
  std::string loss = "none";
  bool no_figures = false;
  PoseGraphOptimizerParams params;
};

Trajectory TrajectoryOf(const PoseGraph& graph, const std::vector<Pose2>& poses) {
  Trajectory t;  // the vertex id stands for the time
  for (std::size_t i = 0; i < poses.size(); ++i) t.push_back({double(graph.vertices[i].id), poses[i]});
  return t;
}

int RunPoseGraphCommand(PoseGraphOptions o) {
  o.params.objective =
      o.objective == "sesync" ? PoseGraphObjective::kSeSync : PoseGraphObjective::kChi2;
  for (const RobustLossKind kind : {RobustLossKind::kHuber, RobustLossKind::kCauchy,
                                    RobustLossKind::kDcs}) {
    if (o.loss == RobustLossName(kind)) o.params.loop_closure_loss.kind = kind;
  }
  std::vector<PoseGraphStart> starts;
  if (o.start != "chordal") starts.push_back(PoseGraphStart::kFile);
  if (o.start != "file") starts.push_back(PoseGraphStart::kChordal);
  OutputDir out(o.out);
  const PoseGraph graph = ReadPoseGraph(o.file);
  PoseGraphRun run;
  try {
    run = RunPoseGraph(graph, starts, o.params);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("{}: {}", o.file, e.what()));
  }
  const auto& dir = out.staging();
  for (const PoseGraphStartResult& r : run.starts) {
    WriteTumTrajectory(dir / fmt::format("trajectory_{}.tum", PoseGraphStartName(r.start)),
                       TrajectoryOf(graph, r.solution.poses));
    fmt::print("{:8} chi2 {:.6g} -> {:.10g}, SE-Sync objective {:.6g} -> {:.10g}, {} iterations, "
               "{:.3f} s{}\n", PoseGraphStartName(r.start), r.solution.initial_chi2,
               r.solution.chi2, r.solution.initial_sesync_objective,
               r.solution.sesync_objective, r.solution.iterations,
               r.initialisation_time_s + r.solution.time_s,
               r.solution.converged ? "" : " (" + r.solution.termination + ")");
  }
  const PoseGraphStartResult& best = run.starts[static_cast<std::size_t>(run.best)];
  PoseGraph optimised = graph;
  for (std::size_t i = 0; i < optimised.vertices.size(); ++i) {
    optimised.vertices[i].pose = best.solution.poses[i];
  }
  WritePoseGraphG2o(dir / "graph.g2o", optimised);
  WriteTumTrajectory(dir / "trajectory.tum", TrajectoryOf(graph, best.solution.poses));
  nlohmann::json metrics = PoseGraphRunJson(graph, run, o.params);
  metrics["file"] = o.file;
  WriteJson(dir / "metrics.json", metrics);
  if (!o.no_figures) {
    PathFigureData figure;
    figure.title = fmt::format("{}: {} start, objective {}", o.file, PoseGraphStartName(best.start),
                               o.objective);
    figure.estimate = TrajectoryOf(graph, best.solution.poses);
    WritePathFigure(dir / "graph.png", figure);
  }
  out.Commit();
  fmt::print("kept the {} start; wrote {}\n", PoseGraphStartName(best.start), o.out);
  return 0;
}

}  // namespace

void RegisterPoseGraph(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<PoseGraphOptions>();
  CLI::App* cmd = app.add_subcommand(
      "posegraph",
      "a 2D pose graph (g2o VERTEX_SE2/EDGE_SE2 or TORO VERTEX2/EDGE2) optimised by "
      "Levenberg-Marquardt on Ceres from the file's values and from a chordal (rotation-first) "
      "start; writes graph.g2o (the better solution), trajectory_START.tum per start, "
      "trajectory.tum, metrics.json (chi2 and SE-Sync's objective before and after, "
      "iterations, times) and graph.png");
  AddExamples(cmd, {
               "../shared/datasets/posegraphs/intel.g2o --objective sesync --out out/intel_g2o"});
  cmd->add_option("file", o->file, "the pose graph file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_option("--objective", o->objective,
                  "chi2 (g2o's) or sesync (SE-Sync's Eq. 12, kappa and tau from the information)")
      ->capture_default_str()
      ->check(CLI::IsMember({"chi2", "sesync"}));
  cmd->add_option("--start", o->start, "file, chordal or both")
      ->capture_default_str()
      ->check(CLI::IsMember({"file", "chordal", "both"}));
  cmd->add_option("--max-iterations", o->params.max_iterations, "Levenberg-Marquardt iterations")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--loss", o->loss,
                  "the loss of loop closures (edges between vertices not consecutive in the "
                  "file): none, huber, cauchy or dcs (dynamic covariance scaling)")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "huber", "cauchy", "dcs"}));
  cmd->add_option("--loss-scale", o->params.loop_closure_loss.scale,
                  "huber and cauchy: the residual's knee; dcs: Phi, in units of chi2")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 1e9));
  cmd->add_option("--threads", o->params.threads, "Ceres threads")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  cmd->add_flag("--no-figures", o->no_figures, "skip graph.png");
  cmd->callback([o, &exit_code] { exit_code = RunPoseGraphCommand(*o); });
}

}  // namespace slamkit::app
