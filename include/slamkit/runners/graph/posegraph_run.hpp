#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/core/pose_graph.hpp"
#include "slamkit/optim/pose_graph_optimizer.hpp"

namespace slamkit {

// `slamkit posegraph`: a g2o or TORO pose graph optimised from two starts.
enum class PoseGraphStart {
  kFile,     // the file's vertex values
  kChordal,  // ChordalInitialization (rotations first)
};
std::string_view PoseGraphStartName(PoseGraphStart start);

struct PoseGraphStartResult {
  PoseGraphStart start = PoseGraphStart::kFile;
  double initialisation_time_s = 0.0;  // the chordal solve; 0 for the file's values
  PoseGraphSolution solution;
};

struct PoseGraphRun {
  std::vector<PoseGraphStartResult> starts;
  int best = 0;  // the start whose solution has the lowest objective
};

// Optimises `graph` from each of `starts`, in order.
PoseGraphRun RunPoseGraph(const PoseGraph& graph, const std::vector<PoseGraphStart>& starts,
                          const PoseGraphOptimizerParams& params);

// metrics.json: the graph's size, the objective minimised, and per start its initial and final
// χ² and SE-Sync objective, iterations, convergence and times; `best` names the start kept.
nlohmann::json PoseGraphRunJson(const PoseGraph& graph, const PoseGraphRun& run,
                                const PoseGraphOptimizerParams& params);

}  // namespace slamkit
