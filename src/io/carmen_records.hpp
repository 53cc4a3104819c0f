#pragma once

// Private to slamkit_io: reading text logs line by line (plain or gzip) and parsing the CARMEN
// records that ReadCarmenLog understands. Every error is an InputError `file:line: RECORD field
// 'name': reason ('token')`.

#include <zlib.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/models/laser_scan.hpp"

namespace slamkit::carmen {

// Physical lines of a plain or gzip-compressed file (zlib detects gzip by the magic bytes 1f 8b
// and reads anything else as is). Throws InputError naming the file when it cannot be opened,
// cannot be read, or ends in the middle of a gzip stream.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its end-of-line characters; false at the end of the file. The view
  // stays valid until the next call.
  bool Next(std::string_view* line);
  int line_number() const { return line_number_; }  // 1-based, of the line Next returned

 private:
  bool Refill();

  std::string path_;
  gzFile file_ = nullptr;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;  // unread bytes are buffer_[begin_, end_)
  std::size_t end_ = 0;
  bool eof_ = false;
  int line_number_ = 0;
};

// Splits at spaces, tabs and carriage returns into `tokens` (cleared first).
void Tokenize(std::string_view line, std::vector<std::string_view>* tokens);

// A field's name for messages: `base` followed by `index` when index >= 0 (r17, rem3).
struct FieldName {
  std::string_view base;
  int index = -1;
};

// The tokens of one record after its kind; field i is tokens[i]. Errors name `where`
// (`file:line`), the record kind (when not empty) and the field.
class Fields {
 public:
  Fields(std::string where, std::string_view kind, std::span<const std::string_view> tokens)
      : where_(std::move(where)), kind_(kind), tokens_(tokens) {}

  std::size_t size() const { return tokens_.size(); }
  std::string_view Text(std::size_t i) const { return tokens_[i]; }
  [[noreturn]] void Fail(const FieldName& field, std::string_view reason) const;
  // Exactly `count` fields, else an error naming the first missing field or the count.
  void Expect(std::size_t count, std::span<const char* const> names) const;
  double Number(std::size_t i, const FieldName& field) const;  // finite
  int Count(std::size_t i, const FieldName& field) const;      // a non-negative integer

 private:
  std::string where_;
  std::string_view kind_;
  std::span<const std::string_view> tokens_;
};

// The front-laser settings that a FLASER record leaves implicit, from the PARAM records so far.
struct FrontLaser {
  double fov_rad = M_PI;
  double max_range_m = 81.83;
  bool max_range_from_laser_param = false;  // laser_front_laser_max_range wins over robot_...
  Pose2 offset;
};

// PARAM name value ...: the name and value; updates `laser` when the name is one of its settings
// (laser_front_laser_fov, laser_front_laser_max_range, robot_front_laser_max,
// robot_frontlaser_offset), whose value must then be a number.
std::pair<std::string, std::string> ParseParam(const Fields& fields, FrontLaser* laser);

// ODOM x y theta tv rv accel timestamp host logger_timestamp.
StampedPose ParseOdom(const Fields& fields);
// The scan records; in the result, odometry holds the record's own odometry fields (FLASER
// odom_x odom_y odom_theta, ROBOTLASER1 robot_x robot_y robot_theta).
LaserScan ParseFlaser(const Fields& fields, const FrontLaser& laser);
LaserScan ParseRobotLaser1(const Fields& fields);

}  // namespace slamkit::carmen
