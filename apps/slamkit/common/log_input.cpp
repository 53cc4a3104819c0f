#include "common/log_input.hpp"

#include <fmt/format.h>

#include <exception>
#include <map>

#include "grid/grid_outputs.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/relations_reader.hpp"
#include "slamkit/io/trajectory_reader.hpp"
#include "slamkit/runners/grid/grid_run.hpp"

namespace slamkit::app {

void AddLogInputOptions(CLI::App* cmd, LogInput& in) {
  CLI::Option* log = cmd->add_option("--log", in.log,
                                     "CARMEN log (.clf/.log, optionally gzip-compressed)")
                          ->check(CLI::ExistingFile);
  cmd->add_option("--bag", in.bag, "ROS 1 bag (sensor_msgs/LaserScan, nav_msgs/Odometry or /tf) "
                                   "instead of --log")
      ->check(CLI::ExistingFile)
      ->excludes(log);
  cmd->add_option("--scan-topic", in.bag_topics.scan_topic, "--bag: the LaserScan topic")
      ->capture_default_str();
  cmd->add_option("--odom-topic", in.bag_topics.odom_topic, "--bag: the Odometry topic")
      ->capture_default_str();
  cmd->add_flag("--tf", in.bag_topics.odometry_from_tf,
                "--bag: the odometry from /tf's --odom-frame -> --base-frame transforms");
  cmd->add_option("--odom-frame", in.bag_topics.odom_frame, "--bag: the odometry frame")
      ->capture_default_str();
  cmd->add_option("--base-frame", in.bag_topics.base_frame, "--bag: the robot's frame")
      ->capture_default_str();
  // Checked with the options, before a --dry-run stops or the command runs.
  cmd->parse_complete_callback([&in] {
    if (in.log.empty() == in.bag.empty()) {
      throw CLI::RequiredError("exactly one of --log and --bag");
    }
  });
  cmd->add_option("--relations", in.relations, "relations file (Kümmerle et al. 2009)")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--skip-bad-lines", in.skip_bad_lines, "skip malformed log lines (counted)");
  cmd->add_option("--max-scans", in.max_scans, "use only the first N scans (0: all)")
      ->check(NonNegativeNumber());
  cmd->add_option("--max-range", in.max_range_m,
                  "the laser's no-return range [m]: a reading at or above it "
                  "is no return "
                  "(default: the log's PARAM, else its largest reading)")
      ->check(PositiveNumber());
  cmd->add_flag("--interpolate-odometry", in.interpolate_odometry,
                "odometry at each scan interpolated from the ODOM records at "
                "the scan's time, "
                "instead of the scan record's own odometry fields");
  cmd->add_option("--reference", in.reference,
                  "reference poses, one per line: `t x y theta` or TUM; ATE "
                  "and RPE against them")
      ->check(CLI::ExistingFile);
  cmd->add_option("--pair-by", in.pair_by,
                  "pair --reference poses with scans by timestamp (time) or by "
                  "order (index)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, PairBy>{{"time", PairBy::kTime}, {"index", PairBy::kIndex}}))
      ->default_str("time");
  cmd->add_flag("--reference-from-log", in.reference_from_log,
                "compare with the poses the log gives (corrected logs): ATE "
                "and RPE, by index")
      ->excludes("--reference");
}

CarmenLog ReadInputLog(const LogInput& in) {
  CarmenReadOptions read_options;
  read_options.skip_bad_lines = in.skip_bad_lines;
  read_options.odometry_from_scan_fields = !in.interpolate_odometry;
  if (in.max_range_m > 0.0) read_options.max_range_m = in.max_range_m;
  CarmenLog log;
  if (in.bag.empty()) {
    log = ReadCarmenLog(in.log, read_options);
  } else {
    RosBagReadOptions bag = in.bag_topics;
    bag.max_range_m = read_options.max_range_m;
    log = ReadRosBag(in.bag, bag);
  }
  if (in.max_scans > 0 && static_cast<int>(log.scans.size()) > in.max_scans) {
    log.scans.resize(in.max_scans);
  }
  if (log.skipped_lines > 0) {
    PrintStderr("{}: skipped {} bad lines\n", in.source(), log.skipped_lines);
  }
  for (const std::string& note : log.notes) PrintStderr("{}: {}\n", in.source(), note);
  return log;
}

std::vector<PoseRelation> ReadInputRelations(const LogInput& in) {
  return in.relations.empty() ? std::vector<PoseRelation>{} : ReadRelations(in.relations);
}

std::optional<Trajectory> LoadReference(const LogInput& in, const CarmenLog& log) {
  if (in.reference_from_log) {
    bool odometry_is_pose = !log.scans.empty();
    for (const LaserScan& scan : log.scans) {
      odometry_is_pose =
          odometry_is_pose && (scan.odometry.vector() - scan.logged_pose.vector()).norm() < 1e-9;
    }
    if (odometry_is_pose) {
      PrintStderr(
          "warning: {}: every scan's odometry equals its logged pose, "
          "so the filter is "
          "given the reference as its odometry and this comparison "
          "measures nothing\n",
          in.source());
    }
    return LoggedTrajectory(log);
  }
  if (in.reference.empty()) return std::nullopt;
  Trajectory reference = ReadTrajectory(in.reference);
  if (in.pair_by == PairBy::kIndex) {
    if (in.max_scans > 0 && reference.size() > log.scans.size()) {
      reference.resize(log.scans.size());
    }
    if (reference.size() != log.scans.size()) {
      throw InputError(
          fmt::format("{}: {} poses for the {} scans of {} (--pair-by index pairs "
                      "pose i with scan i)",
                      in.reference, reference.size(), log.scans.size(), in.source()));
    }
  } else if (const std::string problem = TimestampProblem(reference); !problem.empty()) {
    throw InputError(fmt::format("{}: its timestamps cannot pair poses ({}): use --pair-by index",
                                 in.reference, problem));
  }
  return reference;
}

void AddLogInputMetrics(const LogInput& in, const CarmenLog& log, const LogEvaluation& e,
                        nlohmann::json& metrics) {
  metrics["log"] = in.source();
  if (!in.reference.empty()) {
    metrics["reference"] = in.reference;
    metrics["pair_by"] = in.pair_by == PairBy::kIndex ? "index" : "time";
  }
  metrics["skipped_lines"] = log.skipped_lines;
  metrics["no_return_beams"] = log.no_return_beams;
  metrics["reader_notes"] = log.notes;
  AddBaselineMetrics(e, metrics);
}

LogScoringParams ScoringOf(const LogInput& input) {
  return {.pair_by = input.reference_from_log ? PairBy::kIndex : input.pair_by,
          .partial_log = input.max_scans > 0};
}

int ReportEvaluation(const LogInput& in, const LogEvaluation& e, const std::string& out) {
  if (e.reference) PrintComparison(in.reference_from_log ? "log poses" : "reference", *e.reference);
  fmt::print("wrote {}\n", out);
  if (e.error.empty()) return 0;
  PrintStderr("error: the evaluation failed ({}); the run's outputs are kept in {}\n", e.error,
              out);
  return 1;
}

void PrintRelations(const RelationErrorStats& r) {
  fmt::print("  {:<28}{:>12}\n", "relations: translation [m]",
             fmt::format("{:.4f} ± {:.4f}", r.trans_mean_m, r.trans_std_m));
  fmt::print("  {:<28}{:>12}\n", "relations: rotation [deg]",
             fmt::format("{:.3f} ± {:.3f}", r.rot_mean_deg, r.rot_std_deg));
  if (r.skipped > 0) {
    PrintStderr(
        "warning: {} relations lie outside the run's time span and "
        "were skipped\n",
        r.skipped);
  }
}

Trajectory OdometryFromOrigin(const CarmenLog& log) {
  Trajectory odometry = OdometryTrajectory(log);
  const Pose2 to_origin = odometry.front().pose.Inverse();
  for (StampedPose& p : odometry) p.pose = to_origin.Compose(p.pose);
  return odometry;
}

}  // namespace slamkit::app
