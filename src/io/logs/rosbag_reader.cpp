#include "slamkit/io/rosbag_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "odometry_interpolation.hpp"
#include "rosbag_messages.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

// A frame name without ROS 1's optional leading slash ("/odom" and "odom" are one frame).
std::string Frame(const std::string& name) {
  return !name.empty() && name.front() == '/' ? name.substr(1) : name;
}

class BagConverter {
 public:
  BagConverter(std::string path, const RosBagReadOptions& options)
      : path_(std::move(path)), options_(options) {}

  CarmenLog Convert(const io_detail::BagContents& bag) {
    TakeTransforms(bag.transforms);
    for (const io_detail::BagPose& p : bag.odometry) AddOdometry(p);
    if (odometry_.empty()) {
      Fail(options_.odometry_from_tf
               ? fmt::format("no {} -> {} transform on /tf", options_.odom_frame,
                             options_.base_frame)
               : fmt::format("no messages on {}", options_.odom_topic));
    }
    if (bag.scans.empty()) Fail("no messages on " + options_.scan_topic);
    for (const io_detail::BagScan& s : bag.scans) log_.scans.push_back(ScanOf(s));
    return Finish();
  }

 private:
  [[noreturn]] void Fail(const std::string& reason) const {
    throw InputError(path_ + ": " + reason);
  }

  // The odometry (with odometry_from_tf) and the laser offsets base_frame -> frame.
  void TakeTransforms(const std::vector<io_detail::BagTransform>& transforms) {
    for (const io_detail::BagTransform& t : transforms) {
      const std::string parent = Frame(t.parent), child = Frame(t.child);
      if (options_.odometry_from_tf && parent == Frame(options_.odom_frame) &&
          child == Frame(options_.base_frame)) {
        AddOdometry(t.pose);
      } else if (parent == Frame(options_.base_frame)) {
        offsets_[child] = Pose2(t.pose.x, t.pose.y, t.pose.yaw);  // the last one of a frame
      }
    }
  }

  void AddOdometry(const io_detail::BagPose& p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.yaw)) {
      Fail(fmt::format("an odometry pose at t = {:.9f} s is not finite", p.t_s));
    }
    odometry_.push_back({p.t_s, Pose2(p.x, p.y, p.yaw)});
  }

  LaserScan ScanOf(const io_detail::BagScan& msg) {
    LaserScan scan;
    scan.t_s = msg.t_s;
    std::tie(scan.angle_min_rad, scan.angle_increment_rad) =
        LaserScanAngles(msg.angle_min, msg.angle_increment);
    scan.max_range_m = options_.max_range_m.value_or(msg.range_max);
    if (msg.ranges.empty() || !std::isfinite(scan.angle_min_rad) ||
        !(std::isfinite(scan.angle_increment_rad) && scan.angle_increment_rad > 0.0) ||
        !(std::isfinite(scan.max_range_m) && scan.max_range_m > 0.0)) {
      Fail(fmt::format("the scan at t = {:.9f} s has no beams, or an angle_min, angle_increment "
                       "or range_max that is not finite and positive", msg.t_s));
    }
    scan.ranges_m.reserve(msg.ranges.size());
    const float no_return = static_cast<float>(scan.max_range_m);
    for (float r : msg.ranges) {
      // REP 117: +inf is "nothing within range" (a no-return ray, as a reading at the maximum);
      // NaN, -inf and readings below range_min are no measurement at all (skipped by every use).
      if (r == std::numeric_limits<float>::infinity()) {
        r = no_return;
      } else if (!std::isfinite(r) || r < msg.range_min) {
        r = std::numeric_limits<float>::quiet_NaN();
        ++invalid_readings_;
      }
      scan.ranges_m.push_back(r);
      log_.no_return_beams += r >= scan.max_range_m ? 1 : 0;
    }
    const auto offset = offsets_.find(Frame(msg.frame));
    if (offset != offsets_.end()) {
      scan.laser_offset = offset->second;
    } else {
      missing_offset_ = Frame(msg.frame);
    }
    return scan;
  }

  // Each scan, in the order the bag recorded them (stamps may jitter back, as a log's do), with
  // the odometry at its stamp from the samples sorted by stamp.
  CarmenLog Finish() {
    const auto by_time = [](const auto& a, const auto& b) { return a.t_s < b.t_s; };
    std::stable_sort(odometry_.begin(), odometry_.end(), by_time);
    for (LaserScan& scan : log_.scans) {
      scan.odometry = io_detail::InterpolateOdometry(odometry_, scan.t_s);
      scan.logged_pose = scan.odometry;
    }
    log_.odometry = std::move(odometry_);
    if (invalid_readings_ > 0) {
      log_.notes.push_back(fmt::format("{} readings were NaN, -inf or below range_min: no "
                                       "measurement", invalid_readings_));
    }
    if (!missing_offset_.empty()) {
      log_.notes.push_back(fmt::format("no {} -> {} transform: the laser is taken at the robot's "
                                       "origin", options_.base_frame, missing_offset_));
    }
    return std::move(log_);
  }

  std::string path_;
  RosBagReadOptions options_;
  CarmenLog log_;
  Trajectory odometry_;
  std::map<std::string, Pose2> offsets_;  // base_frame -> frame, by frame
  std::string missing_offset_;
  long long invalid_readings_ = 0;
};

// The multiple of π/denominator that rounds to `value` as float32 (the fraction reduced, so that
// −π/2 is π·(−1)/2 exactly), or `value` itself when none does.
double PiMultipleOrAsRead(float value, long denominator) {
  const long k = std::lround(static_cast<double>(value) * static_cast<double>(denominator) / M_PI);
  const long g = std::gcd(k, denominator);
  const double candidate = M_PI * static_cast<double>(k / g) / static_cast<double>(denominator / g);
  return static_cast<float>(candidate) == value ? candidate : static_cast<double>(value);
}

}  // namespace

std::pair<double, double> LaserScanAngles(float angle_min, float angle_increment) {
  const long n = angle_increment > 0.0f ? std::lround(M_PI / angle_increment) : 0;
  if (n < 1 || n > 100'000) return {angle_min, angle_increment};
  const double step = PiMultipleOrAsRead(angle_increment, n);
  if (step == static_cast<double>(angle_increment)) return {angle_min, angle_increment};
  return {PiMultipleOrAsRead(angle_min, 2 * n), step};
}

CarmenLog ReadRosBag(const std::filesystem::path& path, const RosBagReadOptions& options) {
  io_detail::BagContents bag;
  try {
    bag = io_detail::ReadBagContents(path.string(), options.scan_topic, options.odom_topic,
                                     !options.odometry_from_tf);
  } catch (const io_detail::BagError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
  return BagConverter(path.string(), options).Convert(bag);
}

}  // namespace slamkit
