#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "slamkit/runners/grid_run.hpp"
#include "slamkit/filters/rbpf_grid_slam.hpp"

namespace slamkit::app {

// What `grid` and `gridsim` share: the filter's options, the output files and the summary.

// The RbpfGridSlam options.
void AddGridFilterOptions(CLI::App* cmd, RbpfGridSlamParams& params);

// DIR/trajectory.txt, DIR/trajectory.tum, DIR/map.pgm + map.yaml and DIR/map.png (the README's
// output contract); creates `dir`.
void WriteGridOutputs(const std::filesystem::path& dir, const GridRunResult& result);

// The summary's first lines: counts, wall time, scans per second, peak memory.
void PrintGridRun(const std::string& source, const GridRunResult& result, int particles);

// The summary's rows for a comparison with reference poses (`against`: "log poses", "truth").
void PrintComparison(const std::string& against, const ReferenceComparison& comparison);

}  // namespace slamkit::app
