#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "slamkit/core/relation.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/io/rosbag_reader.hpp"
#include "slamkit/runners/common/log_scoring.hpp"

namespace slamkit::app {

// What the commands that run on a CARMEN log (`grid`, `features`) share: the log's options, its
// reading, the reference poses and relations it is scored against, and that scoring.
struct LogInput {
  std::string log;
  std::string bag;  // a ROS 1 bag instead of --log
  RosBagReadOptions bag_topics;
  std::string relations;
  std::string reference;
  PairBy pair_by = PairBy::kTime;
  bool skip_bad_lines = false;
  bool reference_from_log = false;
  bool interpolate_odometry = false;
  int max_scans = 0;         // 0: all
  double max_range_m = 0.0;  // 0: from the log

  const std::string& source() const { return bag.empty() ? log : bag; }  // the file read
};

// --log or --bag (with --scan-topic, --odom-topic, --tf, --odom-frame, --base-frame),
// --relations, --reference, --pair-by, --reference-from-log, --skip-bad-lines, --max-scans,
// --max-range and --interpolate-odometry.
void AddLogInputOptions(CLI::App* cmd, LogInput& input);

// The log or bag as the options say (its first --max-scans scans), with the reader's notes on stderr.
CarmenLog ReadInputLog(const LogInput& input);

// The relations (--relations) and the reference poses (--reference, --reference-from-log), read
// and checked before the long run: InputError naming the file when they cannot pair with `log`.
std::vector<PoseRelation> ReadInputRelations(const LogInput& input);
std::optional<Trajectory> LoadReference(const LogInput& input, const CarmenLog& log);

// How the options score a run (runners' EvaluateOnLog): the pairing, and whether the run
// covered only the first --max-scans scans.
LogScoringParams ScoringOf(const LogInput& input);

// metrics.json's keys of the input and of the odometry's evaluation: log, reference, pair_by,
// skipped_lines, no_return_beams, reader_notes, odometry_*, evaluation_error.
void AddLogInputMetrics(const LogInput& input, const CarmenLog& log, const LogEvaluation& e,
                        nlohmann::json& metrics);

// After the output is in place (`out`): the comparison's rows (against the "log poses" or the
// "reference"), "wrote DIR", and a failed evaluation's error on stderr. Returns the exit code:
// 1 when the evaluation failed (the outputs are kept), else 0.
int ReportEvaluation(const LogInput& input, const LogEvaluation& e, const std::string& out);

// The summary's relation rows (and a warning for relations outside the run).
void PrintRelations(const RelationErrorStats& r);

// The raw odometry at each scan, moved so that the first scan is at the origin, where the
// filters start.
Trajectory OdometryFromOrigin(const CarmenLog& log);

}  // namespace slamkit::app
