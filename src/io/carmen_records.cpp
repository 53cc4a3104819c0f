#include "carmen_records.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cstring>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit::carmen {
namespace {

constexpr std::size_t kInitialBuffer = std::size_t{1} << 16;
constexpr unsigned kZlibBuffer = 1u << 17;

constexpr const char* kOdomFields[] = {"x",         "y",    "theta",           "tv", "rv", "accel",
                                       "timestamp", "host", "logger_timestamp"};
constexpr const char* kFlaserPoseFields[] = {"x", "y", "theta", "odom_x", "odom_y", "odom_theta"};
constexpr const char* kRobotLaserHead[] = {"laser_type", "start_angle", "fov",
                                           "angular_resolution", "max_range", "accuracy",
                                           "remission_mode", "num_readings"};
constexpr const char* kRobotLaserTail[] = {
    "laser_x", "laser_y", "laser_theta", "robot_x", "robot_y", "robot_theta", "tv", "rv",
    "forward_safety_dist", "side_safety_dist", "turn_axis", "timestamp", "host",
    "logger_timestamp"};
constexpr std::size_t kRobotLaserTailSize = std::size(kRobotLaserTail);

// Reads the pose stored as x, y, theta in fields first .. first + 2.
Pose2 PoseAt(const Fields& fields, std::size_t first, const char* const* names) {
  return Pose2(fields.Number(first, {names[0]}), fields.Number(first + 1, {names[1]}),
               fields.Number(first + 2, {names[2]}));
}

float Range(const Fields& fields, std::size_t i, int beam) {
  const double value = fields.Number(i, {"r", beam});
  if (std::abs(value) > FLT_MAX) fields.Fail({"r", beam}, "out of range");
  return static_cast<float>(value);
}

}  // namespace

LineReader::LineReader(const std::filesystem::path& path)
    : path_(path.string()), buffer_(kInitialBuffer) {
  file_ = gzopen(path_.c_str(), "rb");
  if (file_ == nullptr) throw InputError(path_ + ": cannot open file");
  gzbuffer(file_, kZlibBuffer);
}

LineReader::~LineReader() { gzclose(file_); }

bool LineReader::Next(std::string_view* line) {
  while (true) {
    const char* data = buffer_.data();
    const void* newline = std::memchr(data + begin_, '\n', end_ - begin_);
    if (newline != nullptr || (eof_ && begin_ < end_)) {
      const std::size_t stop =
          newline != nullptr ? static_cast<const char*>(newline) - data : end_;
      *line = std::string_view(data + begin_, stop - begin_);
      if (line->ends_with('\r')) line->remove_suffix(1);
      begin_ = std::min(stop + 1, end_);
      ++line_number_;
      return true;
    }
    if (eof_ || !Refill()) return false;
  }
}

// Moves the unread bytes to the front (growing the buffer for a line longer than it) and reads
// more; false at the end of the file.
bool LineReader::Refill() {
  std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
  end_ -= begin_;
  begin_ = 0;
  if (end_ == buffer_.size()) buffer_.resize(2 * buffer_.size());
  const unsigned room = static_cast<unsigned>(buffer_.size() - end_);
  const int read = gzread(file_, buffer_.data() + end_, room);
  int code = Z_OK;
  const char* message = gzerror(file_, &code);
  if (read < 0) throw InputError(fmt::format("{}: read error ({})", path_, message));
  if (read == 0) {
    if (code == Z_BUF_ERROR) throw InputError(path_ + ": truncated gzip file");
    eof_ = true;
    return begin_ < end_;
  }
  end_ += static_cast<std::size_t>(read);
  return true;
}

void Tokenize(std::string_view line, std::vector<std::string_view>* tokens) {
  tokens->clear();
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i == line.size()) return;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    tokens->push_back(line.substr(start, i - start));
  }
}

void Fields::Fail(const FieldName& field, std::string_view reason) const {
  const std::string name = field.index >= 0 ? fmt::format("{}{}", field.base, field.index)
                                            : std::string(field.base);
  if (kind_.empty()) throw InputError(fmt::format("{}: field '{}': {}", where_, name, reason));
  throw InputError(fmt::format("{}: {} field '{}': {}", where_, kind_, name, reason));
}

void Fields::Expect(std::size_t count, std::span<const char* const> names) const {
  if (size() < count) Fail({names[size()]}, "missing");
  if (size() > count) {
    const std::string kind = kind_.empty() ? "a line" : std::string(kind_);
    throw InputError(fmt::format("{}: {} has {} fields, expected {}", where_, kind, size(), count));
  }
}

double Fields::Number(std::size_t i, const FieldName& field) const {
  const std::string_view text = tokens_[i];
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    Fail(field, fmt::format("not a number ('{}')", text));
  }
  if (!std::isfinite(value)) Fail(field, fmt::format("not a finite number ('{}')", text));
  return value;
}

int Fields::Count(std::size_t i, const FieldName& field) const {
  const std::string_view text = tokens_[i];
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    Fail(field, fmt::format("not an integer ('{}')", text));
  }
  if (value < 0) Fail(field, fmt::format("negative count ('{}')", text));
  return value;
}

std::pair<std::string, std::string> ParseParam(const Fields& fields, FrontLaser* laser) {
  constexpr const char* kNames[] = {"name", "value"};
  if (fields.size() < 2) fields.Fail({kNames[fields.size()]}, "missing");
  std::pair<std::string, std::string> param(fields.Text(0), fields.Text(1));
  const std::string_view name = param.first;
  if (name == "laser_front_laser_fov") {
    // CARMEN documents degrees, but some logs (csail) give radians: no laser sees less than 2π°.
    const double fov = fields.Number(1, {"value"});
    laser->fov_rad = fov > 2.0 * M_PI ? DegToRad(fov) : fov;
  } else if (name == "laser_front_laser_max_range") {
    laser->max_range_m = fields.Number(1, {"value"});
    laser->max_range_from_laser_param = true;
  } else if (name == "robot_front_laser_max" && !laser->max_range_from_laser_param) {
    laser->max_range_m = fields.Number(1, {"value"});
  } else if (name == "robot_frontlaser_offset") {
    laser->offset = Pose2(fields.Number(1, {"value"}), 0.0, 0.0);
  }
  return param;
}

StampedPose ParseOdom(const Fields& fields) {
  fields.Expect(std::size(kOdomFields), kOdomFields);
  for (std::size_t i = 3; i < 6; ++i) fields.Number(i, {kOdomFields[i]});
  fields.Number(8, {"logger_timestamp"});
  return {fields.Number(6, {"timestamp"}), PoseAt(fields, 0, kOdomFields)};
}

LaserScan ParseFlaser(const Fields& fields, const FrontLaser& laser) {
  if (fields.size() == 0) fields.Fail({"n"}, "missing");
  const int n = fields.Count(0, {"n"});
  const std::size_t expected = static_cast<std::size_t>(n) + 10;
  if (fields.size() != expected) {
    fields.Fail({"n"}, fmt::format("{} readings need {} fields after FLASER, got {}", n, expected,
                                   fields.size()));
  }
  LaserScan scan;
  scan.ranges_m.resize(n);
  for (int i = 0; i < n; ++i) scan.ranges_m[i] = Range(fields, 1 + i, i + 1);
  const std::size_t pose = static_cast<std::size_t>(n) + 1;
  scan.logged_pose = PoseAt(fields, pose, kFlaserPoseFields);
  scan.odometry = PoseAt(fields, pose + 3, kFlaserPoseFields + 3);
  scan.t_s = fields.Number(pose + 6, {"timestamp"});
  fields.Number(pose + 8, {"logger_timestamp"});
  // n even (180 beams at 1°): the beams start at -fov/2 and stop one increment short of +fov/2;
  // n odd (181 or 361 beams): both ends of the field of view are included.
  scan.angle_min_rad = -laser.fov_rad / 2.0;
  scan.angle_increment_rad = n > 1 && n % 2 == 1 ? laser.fov_rad / (n - 1) : laser.fov_rad / n;
  scan.max_range_m = laser.max_range_m;
  scan.laser_offset = laser.offset;
  return scan;
}

LaserScan ParseRobotLaser1(const Fields& fields) {
  const std::size_t head = std::size(kRobotLaserHead);
  if (fields.size() < head) fields.Fail({kRobotLaserHead[fields.size()]}, "missing");
  const int n = fields.Count(head - 1, {"num_readings"});
  const std::size_t remissions = head + static_cast<std::size_t>(n);
  if (fields.size() <= remissions) fields.Fail({"num_remissions"}, "missing");
  const int m = fields.Count(remissions, {"num_remissions"});
  const std::size_t tail = remissions + 1 + static_cast<std::size_t>(m);
  if (fields.size() != tail + kRobotLaserTailSize) {
    fields.Fail({"num_readings"}, fmt::format("{} readings and {} remissions need {} fields after "
                                              "ROBOTLASER1, got {}",
                                              n, m, tail + kRobotLaserTailSize, fields.size()));
  }
  for (std::size_t i = 0; i + 1 < head; ++i) fields.Number(i, {kRobotLaserHead[i]});
  LaserScan scan;
  scan.angle_min_rad = fields.Number(1, {"start_angle"});
  scan.angle_increment_rad = fields.Number(3, {"angular_resolution"});
  scan.max_range_m = fields.Number(4, {"max_range"});
  scan.ranges_m.resize(n);
  for (int i = 0; i < n; ++i) scan.ranges_m[i] = Range(fields, head + i, i + 1);
  for (int i = 0; i < m; ++i) fields.Number(remissions + 1 + i, {"rem", i + 1});
  const Pose2 laser = PoseAt(fields, tail, kRobotLaserTail);
  scan.logged_pose = PoseAt(fields, tail + 3, kRobotLaserTail + 3);
  scan.odometry = scan.logged_pose;
  scan.laser_offset = scan.logged_pose.Between(laser);
  for (std::size_t i = 6; i < 11; ++i) fields.Number(tail + i, {kRobotLaserTail[i]});
  scan.t_s = fields.Number(tail + 11, {"timestamp"});
  fields.Number(tail + 13, {"logger_timestamp"});
  return scan;
}

}  // namespace slamkit::carmen
