#include "slamkit/io/isam_reader.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "slamkit/io/error.hpp"
#include "../text/text_records.hpp"

namespace slamkit {
namespace {

constexpr const char* kOdometryFields[] = {
    "i", "j", "dx", "dy", "dtheta", "c_xx", "c_xy", "c_xtheta", "c_yy", "c_ytheta", "c_thetatheta"};
constexpr const char* kLandmarkFields[] = {"i", "l", "x", "y", "c_xx", "c_xy", "c_yy"};

// One whitespace-separated record; `where` (`file:line`) prefixes every error.
class Record {
 public:
  Record(std::string where, std::vector<std::string> tokens)
      : where_(std::move(where)), tokens_(std::move(tokens)) {}

  [[noreturn]] void Fail(const std::string& reason) const {
    throw InputError(where_ + ": " + reason);
  }
  const std::string& Kind() const { return tokens_[0]; }

  // Checks the field count against the names of the fields after the record kind.
  template <std::size_t N>
  void ExpectFields(const char* const (&names)[N]) {
    names_ = names;
    if (tokens_.size() - 1 < N) Fail(fmt::format("field '{}': missing", names[tokens_.size() - 1]));
    if (tokens_.size() - 1 > N) {
      Fail(fmt::format("{} expects {} fields, got {}", Kind(), N, tokens_.size() - 1));
    }
  }

  int Int(int field) const {
    const std::string& text = tokens_[field + 1];
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
      Fail(fmt::format("field '{}': not an integer ('{}')", names_[field], text));
    }
    return value;
  }

  double Number(int field) const {
    const std::string& text = tokens_[field + 1];
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
      Fail(fmt::format("field '{}': not a number ('{}')", names_[field], text));
    }
    if (!std::isfinite(value)) {
      Fail(fmt::format("field '{}': not a finite number ('{}')", names_[field], text));
    }
    return value;
  }

  // A number within [-bound, bound]; `unit` names the bound's unit in the message.
  double Bounded(int field, double bound, const char* unit) const {
    const double value = Number(field);
    if (std::abs(value) > bound) {
      Fail(fmt::format("field '{}': magnitude above {:g} {} ('{}')", names_[field], bound, unit,
                       tokens_[field + 1]));
    }
    return value;
  }

  // A symmetric covariance from its upper triangle, stored row by row from field `first`.
  template <int D>
  Eigen::Matrix<double, D, D> Covariance(int first, const char* what) const {
    Eigen::Matrix<double, D, D> c;
    int field = first;
    for (int r = 0; r < D; ++r) {
      for (int k = r; k < D; ++k) {
        c(r, k) = c(k, r) = Bounded(field++, kIsamMaxVariance, "(variance)");
      }
    }
    if (Eigen::LLT<Eigen::Matrix<double, D, D>>(c).info() != Eigen::Success) {
      Fail(fmt::format("{} covariance is not positive definite", what));
    }
    return c;
  }

 private:
  std::string where_;
  std::vector<std::string> tokens_;
  const char* const* names_ = nullptr;
};

std::vector<std::string> Tokens(const std::string& line) {
  std::istringstream stream(line);
  std::vector<std::string> tokens;
  for (std::string token; stream >> token;) tokens.push_back(token);
  return tokens;
}

// Follows the pose chain: the first record fixes the initial pose, later ones must start from
// the latest pose.
class IsamParser {
 public:
  void Parse(Record& record) {
    if (record.Kind() == "ODOMETRY") {
      Odometry(record);
    } else if (record.Kind() == "LANDMARK") {
      Landmark(record);
    } else {
      record.Fail(fmt::format("unknown record '{}' (expected ODOMETRY or LANDMARK, an iSAM log)",
                              text::Printable(record.Kind())));
    }
  }
  bool empty() const { return !latest_; }
  IsamLog Take() { return std::move(log_); }

 private:
  void CheckFrom(const Record& record, int from, const char* what) {
    if (!latest_) {
      latest_ = from;
      log_.initial_pose_index = from;
    } else if (from != *latest_) {
      record.Fail(fmt::format("{} from pose {} breaks the chain (latest pose is {})", what, from,
                              *latest_));
    }
  }

  void Odometry(Record& record) {
    record.ExpectFields(kOdometryFields);
    CheckFrom(record, record.Int(0), "ODOMETRY");
    IsamStep step;
    step.pose_index = record.Int(1);
    step.odometry = {record.Bounded(2, kIsamMaxMagnitude, "m"),
                     record.Bounded(3, kIsamMaxMagnitude, "m"),
                     record.Bounded(4, kIsamMaxMagnitude, "rad")};
    step.odometry_covariance = record.Covariance<3>(5, "odometry");
    latest_ = step.pose_index;
    log_.steps.push_back(std::move(step));
  }

  void Landmark(Record& record) {
    record.ExpectFields(kLandmarkFields);
    CheckFrom(record, record.Int(0), "LANDMARK");
    PointObservation obs;
    obs.id = record.Int(1);
    if (obs.id < 0) record.Fail(fmt::format("field 'l': negative landmark id ({})", obs.id));
    obs.z = {record.Bounded(2, kIsamMaxMagnitude, "m"), record.Bounded(3, kIsamMaxMagnitude, "m")};
    obs.R = record.Covariance<2>(4, "landmark");
    auto& sightings = log_.steps.empty() ? log_.initial_sightings : log_.steps.back().sightings;
    sightings.push_back(obs);
  }

  IsamLog log_;
  std::optional<int> latest_;
};

}  // namespace

IsamLog ReadIsamLog(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open file");
  IsamParser parser;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    if (line_number == 1 && line.starts_with("#ROSBAG")) {
      throw InputError(path.string() +
                       ":1: a ROS bag (#ROSBAG header), expected an iSAM log (ODOMETRY and "
                       "LANDMARK lines)");
    }
    std::vector<std::string> tokens = Tokens(line);
    if (tokens.empty() || tokens[0].starts_with('#')) continue;
    Record record(fmt::format("{}:{}", path.string(), line_number), std::move(tokens));
    parser.Parse(record);
  }
  if (in.bad()) throw InputError(path.string() + ": read error");
  if (parser.empty()) {
    throw InputError(path.string() +
                     ": no records (expected an iSAM log: ODOMETRY and LANDMARK lines)");
  }
  return parser.Take();
}

}  // namespace slamkit
