#pragma once

// For `grid` and `gridsim`: the filter's options, the output files and the summary.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "slamkit/runners/grid/grid_run.hpp"
#include "slamkit/runners/grid/hypotheses.hpp"

namespace slamkit::app {

// The grid filter's options: the lines of GridParamTable(config) with a flag, and the shortcuts
// for its proposal and tracking modes; returns them (so that --config can exclude them).
std::vector<CLI::Option*> AddGridFilterOptions(CLI::App* cmd, GridSlamConfig& config);

// DIR/trajectory.txt, DIR/trajectory.tum, DIR/map.pgm + map.yaml and DIR/map.png (the README's
// output contract; the PNG is the map figure, titled `title`, with the path and, dimmer, the
// odometry over it), and DIR/odometry.tum when `odometry` is not empty; creates `dir`. TUM times
// are made strictly increasing (WithIncreasingTimes, 1 µs steps) for evo; trajectory.txt keeps
// the log's. Returns how many of trajectory.tum's times were moved.
int WriteGridOutputs(const std::filesystem::path& dir, const GridRunResult& result,
                     const Trajectory& odometry = {}, const std::string& title = "");

// P-SLAM's outputs (SPEC S4): DIR/hypotheses.csv (a line per prediction request: its time and
// scans, target, Ψ, predicted area, similarity with the final map, best hit ratio and fate),
// DIR/predicted.pgm + predicted.yaml (the predicted cells where the map is unknown) and
// DIR/map_predicted.png (the map with those cells in orange).
void WritePredictionOutputs(const std::filesystem::path& dir, const GridRunResult& result,
                            const std::vector<HypothesisRow>& hypotheses,
                            const OccupancyGrid& predicted);

// The summary's first lines: counts, wall time, scans per second, peak memory.
void PrintGridRun(const std::string& source, const GridRunResult& result, int particles);
// The summary's line for a run's fit of its odometry's heading drift (none without a fit).
void PrintHeadingDrift(const std::optional<HeadingDriftFit>& fit);

// The summary's rows for a comparison with reference poses (`against`: "log poses", "truth").
void PrintComparison(const std::string& against, const ReferenceComparison& comparison);

}  // namespace slamkit::app
