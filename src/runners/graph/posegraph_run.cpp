#include "slamkit/runners/graph/posegraph_run.hpp"

#include <chrono>

namespace slamkit {
namespace {

double Objective(const PoseGraphSolution& s, PoseGraphObjective objective) {
  return objective == PoseGraphObjective::kSeSync ? s.sesync_objective : s.chi2;
}

}  // namespace

std::string_view PoseGraphStartName(PoseGraphStart start) {
  return start == PoseGraphStart::kChordal ? "chordal" : "file";
}

PoseGraphRun RunPoseGraph(const PoseGraph& graph, const std::vector<PoseGraphStart>& starts,
                          const PoseGraphOptimizerParams& params) {
  PoseGraphRun run;
  for (const PoseGraphStart start : starts) {
    PoseGraphStartResult r;
    r.start = start;
    std::vector<Pose2> initial;
    if (start == PoseGraphStart::kChordal) {
      const auto t0 = std::chrono::steady_clock::now();
      initial = ChordalInitialization(graph);
      r.initialisation_time_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    } else {
      initial = InitialPoses(graph);
    }
    r.solution = OptimizePoseGraph(graph, initial, params);
    run.starts.push_back(std::move(r));
    const auto& kept = run.starts[static_cast<std::size_t>(run.best)].solution;
    if (Objective(run.starts.back().solution, params.objective) <
        Objective(kept, params.objective)) {
      run.best = static_cast<int>(run.starts.size()) - 1;
    }
  }
  return run;
}

nlohmann::json PoseGraphRunJson(const PoseGraph& graph, const PoseGraphRun& run,
                                const PoseGraphOptimizerParams& params) {
  nlohmann::json j;
  j["vertices"] = graph.vertices.size();
  j["edges"] = graph.edges.size();
  j["objective"] = params.objective == PoseGraphObjective::kSeSync ? "sesync" : "chi2";
  j["params"] = {{"max_iterations", params.max_iterations},
                 {"function_tolerance", params.function_tolerance},
                 {"gradient_tolerance", params.gradient_tolerance},
                 {"parameter_tolerance", params.parameter_tolerance},
                 {"threads", params.threads},
                 {"loop_closure_loss", RobustLossName(params.loop_closure_loss.kind)},
                 {"loop_closure_loss_scale", params.loop_closure_loss.scale}};
  for (const PoseGraphStartResult& r : run.starts) {
    const PoseGraphSolution& s = r.solution;
    j["starts"][std::string(PoseGraphStartName(r.start))] = {
        {"initial_chi2", s.initial_chi2},
        {"initial_sesync_objective", s.initial_sesync_objective},
        {"chi2", s.chi2},
        {"sesync_objective", s.sesync_objective},
        {"iterations", s.iterations},
        {"converged", s.converged},
        {"termination", s.termination},
        {"initialisation_time_s", r.initialisation_time_s},
        {"optimisation_time_s", s.time_s}};
  }
  if (!run.starts.empty()) {
    j["best"] = PoseGraphStartName(run.starts[static_cast<std::size_t>(run.best)].start);
  }
  return j;
}

}  // namespace slamkit
