#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "slamkit/runners/grid_run.hpp"
#include "slamkit/filters/rbpf_grid_slam.hpp"

namespace slamkit::app {

// What the commands share: number checks that say their range in words, the output directory's
// check; and for `grid` and `gridsim`, the filter's options, the output files and the summary.

// CLI11 checks for a number > 0 and >= 0 whose message says so ("must be > 0, got 0"), where
// CLI::PositiveNumber's says "not in range 0.000000 to 1797693134862315708...".
CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();

// Checks, before a run, that `out` (--out) can be the output directory: not empty, not an
// existing non-directory, and creatable and writable. Creates it. Throws InputError naming it.
void PrepareOutputDir(const std::string& out);

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
