#include "slamkit/io/carmen_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "carmen_records.hpp"
#include "odometry_interpolation.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

// A timestamp may fall behind its stream's previous one by this much (rounding in the log).
constexpr double kTimeToleranceS = 1e-6;

// 0 (or, in GMapping-written logs, a denormal like 1.08499e-42) stands for "no timestamp": such
// a record is neither ordered nor placed in time.
bool HasTimestamp(double t_s) { return t_s >= 1e-6; }

// The latest timestamp of one stream (ODOM, or scans) and its line, for the ordering check.
struct StreamClock {
  double t_s = 0.0;
  int line = 0;  // 0: no record yet
};

// Turns the records of one log into a CarmenLog, line by line.
class CarmenParser {
 public:
  CarmenParser(const std::filesystem::path& path, const CarmenReadOptions& options)
      : file_(path.string()), options_(options) {}

  // One non-blank, non-comment line; throws InputError for a malformed one.
  void Parse(std::span<const std::string_view> tokens, int line) {
    const std::string_view kind = tokens[0];
    const text::Fields fields(fmt::format("{}:{}", file_, line), kind, tokens.subspan(1));
    if (kind == "ODOM") {
      const StampedPose odom = carmen::ParseOdom(fields);
      Tick(fields, odom.t_s, line, &odom_clock_);
      log_.odometry.push_back(odom);
    } else if (kind == "FLASER") {
      AddScan(fields, carmen::ParseFlaser(fields, laser_), line);
      (laser_.max_range_m ? param_ranged_ : unranged_).push_back(log_.scans.size() - 1);
    } else if (kind == "ROBOTLASER1") {
      AddScan(fields, carmen::ParseRobotLaser1(fields), line);
    } else if (kind == "PARAM") {
      auto [name, value] = carmen::ParseParam(fields, &laser_);
      log_.params[std::move(name)] = std::move(value);
    }
  }

  CarmenLog Finish();
  bool has_scans() const { return !log_.scans.empty(); }

 private:
  void SetMaxRanges();
  void DropContradictedParams();
  void CountNoReturns();
  void InterpolateScanOdometry();

  void AddScan(const text::Fields& fields, LaserScan scan, int line) {
    Tick(fields, scan.t_s, line, &scan_clock_);
    log_.scans.push_back(std::move(scan));
  }

  // Checks that t_s does not go back in its stream, then advances the stream's clock.
  void Tick(const text::Fields& fields, double t_s, int line, StreamClock* clock) {
    if (!HasTimestamp(t_s)) return;
    if (clock->line > 0 && t_s < clock->t_s - kTimeToleranceS) {
      if (t_s < clock->t_s - options_.max_time_step_back_s) {
        fields.Fail({"timestamp"}, fmt::format("time goes backwards ({:.6f} < {:.6f} on line {})",
                                               t_s, clock->t_s, clock->line));
      }
      ++log_.time_steps_back;
    }
    *clock = {t_s, line};
  }

  std::string file_;
  CarmenReadOptions options_;
  carmen::FrontLaser laser_;
  StreamClock odom_clock_;
  StreamClock scan_clock_;
  CarmenLog log_;
  std::vector<std::size_t> unranged_;      // FLASER scans that no PARAM gave a max range
  std::vector<std::size_t> param_ranged_;  // FLASER scans whose max range a PARAM gave
};

// A PARAM max range is the sensor's no-return range only if (nearly) no reading exceeds it:
// edmonton's `robot_front_laser_max 10` sits under a third of its readings (up to 51 m), and
// trusting it made every return beyond 10 m a no-return, erasing the walls of its open halls.
constexpr double kParamSlackM = 0.01;          // readings written with rounding above the PARAM
constexpr double kContradictingShare = 0.001;  // more readings than this above it: not a max

// The PARAM max ranges that the readings contradict (see kContradictingShare): their scans get
// the range derived from the data instead, and the log says so in its notes.
void CarmenParser::DropContradictedParams() {
  std::map<double, std::vector<std::size_t>> by_range;
  for (std::size_t k : param_ranged_) by_range[log_.scans[k].max_range_m].push_back(k);
  for (const auto& [range, scans] : by_range) {
    std::size_t finite = 0, above = 0;
    for (std::size_t k : scans) {
      for (float r : log_.scans[k].ranges_m) {
        if (!std::isfinite(r)) continue;
        ++finite;
        above += r > range + kParamSlackM ? 1 : 0;
      }
    }
    if (above <= kContradictingShare * static_cast<double>(finite)) continue;
    unranged_.insert(unranged_.end(), scans.begin(), scans.end());
    log_.notes.push_back(fmt::format(
        "PARAM max range {:g} m is not the laser's: {} of {} readings of its {} scans lie above "
        "it, so their no-return range comes from the readings instead",
        range, above, finite, scans.size()));
  }
}

// The no-return range of the scans that no (uncontradicted) PARAM covers: their largest
// reading (see the header); then the user's override over every scan.
void CarmenParser::SetMaxRanges() {
  DropContradictedParams();
  float largest = 0.0f;
  for (std::size_t k : unranged_) {
    for (float r : log_.scans[k].ranges_m) {
      if (std::isfinite(r)) largest = std::max(largest, r);
    }
  }
  const double derived = largest > 0.0f ? double(largest) : std::numeric_limits<double>::infinity();
  for (std::size_t k : unranged_) log_.scans[k].max_range_m = derived;
  if (options_.max_range_m) {
    for (LaserScan& scan : log_.scans) scan.max_range_m = *options_.max_range_m;
  }
  CountNoReturns();
}

// Finite, positive readings at or beyond the scan's no-return range.
void CarmenParser::CountNoReturns() {
  for (const LaserScan& scan : log_.scans) {
    for (float r : scan.ranges_m) {
      log_.no_return_beams += std::isfinite(r) && r > 0.0f && r >= scan.max_range_m ? 1 : 0;
    }
  }
}

// Odometry at each scan's time from the ODOM records that have one. GMapping-written logs follow
// every scan with an `ODOM ... 0 pippo 0` copy of its corrected pose: sorted by time, those
// copies came first and gave their pose to the scans before the first stamped record (and to
// scans without a timestamp). A scan without a timestamp, or in a log whose ODOM records have
// none, keeps its own fields.
void CarmenParser::InterpolateScanOdometry() {
  if (log_.odometry.empty()) return;
  Trajectory stamped;
  for (const StampedPose& record : log_.odometry) {
    if (HasTimestamp(record.t_s)) stamped.push_back(record);
  }
  const std::size_t unstamped = log_.odometry.size() - stamped.size();
  if (stamped.empty()) {
    log_.notes.push_back(fmt::format("none of the {} ODOM records has a timestamp, so the "
                                     "odometry comes from the scan records' own fields",
                                     unstamped));
    return;
  }
  if (unstamped > 0) {
    log_.notes.push_back(fmt::format("{} of {} ODOM records have no timestamp and are not used "
                                     "to interpolate the odometry",
                                     unstamped, log_.odometry.size()));
  }
  std::stable_sort(stamped.begin(), stamped.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.t_s < b.t_s; });
  std::size_t unstamped_scans = 0;
  for (LaserScan& scan : log_.scans) {
    if (HasTimestamp(scan.t_s)) {
      scan.odometry = io_detail::InterpolateOdometry(stamped, scan.t_s);
    } else {
      ++unstamped_scans;
    }
  }
  if (unstamped_scans > 0) {
    log_.notes.push_back(fmt::format("{} of {} scans have no timestamp, so their odometry comes "
                                     "from their own fields",
                                     unstamped_scans, log_.scans.size()));
  }
}

CarmenLog CarmenParser::Finish() {
  SetMaxRanges();
  if (!options_.odometry_from_scan_fields) InterpolateScanOdometry();
  return std::move(log_);
}

}  // namespace

CarmenLog ReadCarmenLog(const std::filesystem::path& path, const CarmenReadOptions& options) {
  text::LineReader reader(path);
  CarmenParser parser(path, options);
  int skipped = 0;
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.Next(&line)) {
    if (reader.line_number() == 1 && line.starts_with("#ROSBAG")) {
      throw InputError(path.string() +
                       ":1: a ROS bag (#ROSBAG header), expected a CARMEN log (FLASER, "
                       "ROBOTLASER1, ODOM, PARAM lines)");
    }
    text::Tokenize(line, &tokens);
    if (tokens.empty() || tokens[0].starts_with('#')) continue;
    try {
      parser.Parse(tokens, reader.line_number());
    } catch (const InputError&) {
      if (!options.skip_bad_lines) throw;
      ++skipped;
    }
  }
  if (!parser.has_scans()) {
    throw InputError(path.string() +
                     ": no laser scans (expected a CARMEN log with FLASER or ROBOTLASER1 "
                     "records)");
  }
  CarmenLog log = parser.Finish();
  log.skipped_lines = skipped;
  return log;
}

}  // namespace slamkit
