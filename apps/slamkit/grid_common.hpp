#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "slamkit/filters/ekf/ekf_slam.hpp"
#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/runners/grid/grid_run.hpp"

namespace slamkit::app {

// What the commands share: number checks that say their range in words, the output directory's
// check; and for `grid` and `gridsim`, the filter's options, the output files and the summary.

// CLI11 checks for a number > 0 and >= 0 whose message says so ("must be > 0, got 0"), where
// CLI::PositiveNumber's says "not in range 0.000000 to 1797693134862315708...".
// "known", "joint-compatibility" or "nearest-neighbour", for summaries.
const char* AssociationName(AssociationMethod m);

CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();
// A seed: digits only, 0 to 2^64 - 1 (CLI11 would read "-1" as 2^64 - 1).
CLI::Validator SeedNumber();

// "1-5", "1,3,7" or "2" as the list of seeds (`--seeds`); InputError naming --seeds otherwise.
std::vector<std::uint64_t> ParseSeeds(const std::string& text);

// A run's output directory (--out), made before the run and put in place after it: the run
// writes into a fresh hidden folder beside it (`.NAME.partial-XXXXXX`), which Commit() renames
// onto `out` in one step (an existing `out` is swapped with it, then removed). So `out` holds
// either its old content or the whole new output, never a mix; a failed run removes its folder
// (an interrupted one leaves it, hidden, beside `out`).
class OutputDir {
 public:
  // Throws InputError naming `out` if it cannot be the output: empty, an existing
  // non-directory, a directory holding other files than an earlier output (no metrics.json),
  // or a place where no folder can be made.
  explicit OutputDir(const std::string& out);
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  ~OutputDir();

  // Where the run writes its files.
  const std::filesystem::path& staging() const { return staging_; }
  // Puts the written output in place of `out`.
  void Commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

// The RbpfGridSlam options; returns them (so that --config can exclude them).
std::vector<CLI::Option*> AddGridFilterOptions(CLI::App* cmd, RbpfGridSlamParams& params);

// DIR/trajectory.txt, DIR/trajectory.tum, DIR/map.pgm + map.yaml and DIR/map.png (the README's
// output contract; the PNG is the map figure, titled `title`, with the path and, dimmer, the
// odometry over it), and DIR/odometry.tum when `odometry` is not empty; creates `dir`. TUM times
// are made strictly increasing (WithIncreasingTimes, 1 µs steps) for evo; trajectory.txt keeps
// the log's. Returns how many of trajectory.tum's times were moved.
int WriteGridOutputs(const std::filesystem::path& dir, const GridRunResult& result,
                     const Trajectory& odometry = {}, const std::string& title = "");

// The summary's first lines: counts, wall time, scans per second, peak memory.
void PrintGridRun(const std::string& source, const GridRunResult& result, int particles);
// The summary's line for a run's fit of its odometry's heading drift (none without a fit).
void PrintHeadingDrift(const std::optional<HeadingDriftFit>& fit);

// The summary's rows for a comparison with reference poses (`against`: "log poses", "truth").
void PrintComparison(const std::string& against, const ReferenceComparison& comparison);

}  // namespace slamkit::app
