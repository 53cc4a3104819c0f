// The UTIAS MRCLAM data sets' text files (Leung, Halpern, Barfoot, Liu, IJRR 2011).
#include "slamkit/io/mrclam_reader.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>

#include <fmt/format.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"
#include "../text/text_records.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxRangeM = 1000.0;
constexpr double kMaxBearingRad = 2.0 * std::numbers::pi;
constexpr double kMaxCoordinateM = 1e6;

fs::path Existing(const fs::path& dir, const std::string& name) {
  const fs::path path = dir / name;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: missing (an MRCLAM folder has Barcodes.dat, "
                                 "Landmark_Groundtruth.dat and RobotN_*.dat)",
                                 path.string()));
  }
  return path;
}

// A record's time, no earlier than the record before it in the same file.
double TimeField(const text::Fields& f, double* previous) {
  const double t = f.Number(0, {"time"});
  if (t < *previous) {
    f.Fail({"time"}, fmt::format("{} is earlier than the line before ({}): the file must be in "
                                 "time order", f.Text(0), *previous));
  }
  *previous = t;
  return t;
}

double Bounded(const text::Fields& f, std::size_t i, const char* name, double lo, double hi) {
  const double v = f.Number(i, {name});
  if (v < lo || v > hi) f.Fail({name}, fmt::format("{} is outside [{}, {}]", f.Text(i), lo, hi));
  return v;
}

// subject → barcode in the file; read as barcode → subject.
std::unordered_map<int, int> ReadBarcodes(const fs::path& path) {
  std::unordered_map<int, int> subject_of;
  text::ForEachRecord(path, [&](const text::Fields& f) {
    static constexpr const char* kNames[] = {"subject", "barcode"};
    f.Expect(2, kNames);
    const int subject = f.Count(0, {"subject"});
    const int barcode = f.Count(1, {"barcode"});
    if (!subject_of.emplace(barcode, subject).second) {
      f.Fail({"barcode"}, fmt::format("barcode {} is mapped twice", barcode));
    }
  });
  return subject_of;
}

std::map<int, Eigen::Vector2d> ReadLandmarks(const fs::path& path) {
  std::map<int, Eigen::Vector2d> landmarks;
  text::ForEachRecord(path, [&](const text::Fields& f) {
    static constexpr const char* kNames[] = {"subject", "x", "y", "x std-dev", "y std-dev"};
    f.Expect(5, kNames);
    const int subject = f.Count(0, {"subject"});
    const Eigen::Vector2d p(Bounded(f, 1, "x", -kMaxCoordinateM, kMaxCoordinateM),
                            Bounded(f, 2, "y", -kMaxCoordinateM, kMaxCoordinateM));
    Bounded(f, 3, "x std-dev", 0.0, kMaxCoordinateM);
    Bounded(f, 4, "y std-dev", 0.0, kMaxCoordinateM);
    if (!landmarks.emplace(subject, p).second) {
      f.Fail({"subject"}, fmt::format("landmark {} is listed twice", subject));
    }
  });
  return landmarks;
}

void ReadOdometry(const fs::path& path, MrclamRobot* robot) {
  double previous = -INFINITY;
  text::ForEachRecord(path, [&](const text::Fields& f) {
    static constexpr const char* kNames[] = {"time", "forward velocity", "angular velocity"};
    f.Expect(3, kNames);
    const double t = TimeField(f, &previous);
    robot->odometry.push_back({t, Bounded(f, 1, "forward velocity", -100.0, 100.0),
                               Bounded(f, 2, "angular velocity", -100.0, 100.0)});
  });
}

void ReadGroundTruth(const fs::path& path, MrclamRobot* robot) {
  double previous = -INFINITY;
  text::ForEachRecord(path, [&](const text::Fields& f) {
    static constexpr const char* kNames[] = {"time", "x", "y", "orientation"};
    f.Expect(4, kNames);
    const double t = TimeField(f, &previous);
    const double x = Bounded(f, 1, "x", -kMaxCoordinateM, kMaxCoordinateM);
    const double y = Bounded(f, 2, "y", -kMaxCoordinateM, kMaxCoordinateM);
    const double theta = Bounded(f, 3, "orientation", -kMaxBearingRad, kMaxBearingRad);
    robot->truth.push_back({t, Pose2(x, y, WrapAngle(theta))});
  });
}

// Sightings of barcodes Barcodes.dat lacks are counted, not kept; a known barcode must name a
// robot of the folder or a surveyed landmark.
void ReadMeasurements(const fs::path& path, const std::unordered_map<int, int>& subject_of,
                      const std::map<int, Eigen::Vector2d>& landmarks, int robots,
                      MrclamRobot* robot) {
  double previous = -INFINITY;
  text::ForEachRecord(path, [&](const text::Fields& f) {
    static constexpr const char* kNames[] = {"time", "barcode", "range", "bearing"};
    f.Expect(4, kNames);
    const double t = TimeField(f, &previous);
    const int barcode = f.Count(1, {"barcode"});
    const double range = Bounded(f, 2, "range", 0.0, kMaxRangeM);
    const double bearing = Bounded(f, 3, "bearing", -kMaxBearingRad, kMaxBearingRad);
    const auto it = subject_of.find(barcode);
    if (it == subject_of.end()) {
      ++robot->unknown_barcodes;
      return;
    }
    const int subject = it->second;
    if ((subject < 1 || subject > robots) && !landmarks.contains(subject)) {
      f.Fail({"barcode"}, fmt::format("barcode {} is subject {}, neither a robot (1 to {}) nor "
                                      "a landmark of Landmark_Groundtruth.dat",
                                      barcode, subject, robots));
    }
    robot->sightings.push_back({t, subject, range, WrapAngle(bearing)});
  });
}

}  // namespace

MrclamDataset ReadMrclam(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(fmt::format("{}: not a folder (an MRCLAM data set is a folder)",
                                 dir.string()));
  }
  int robots = 0;
  while (fs::is_regular_file(dir / fmt::format("Robot{}_Odometry.dat", robots + 1), ec)) ++robots;
  if (robots == 0) {
    throw InputError(fmt::format("{}: no Robot1_Odometry.dat: not an MRCLAM data set",
                                 dir.string()));
  }
  MrclamDataset data;
  const auto subject_of = ReadBarcodes(Existing(dir, "Barcodes.dat"));
  data.landmarks = ReadLandmarks(Existing(dir, "Landmark_Groundtruth.dat"));
  for (int n = 1; n <= robots; ++n) {
    if (data.landmarks.contains(n)) {
      throw InputError(fmt::format("{}: subject {} is robot {} and a landmark",
                                   (dir / "Landmark_Groundtruth.dat").string(), n, n));
    }
    MrclamRobot robot;
    robot.subject = n;
    ReadOdometry(Existing(dir, fmt::format("Robot{}_Odometry.dat", n)), &robot);
    ReadMeasurements(Existing(dir, fmt::format("Robot{}_Measurement.dat", n)), subject_of,
                     data.landmarks, robots, &robot);
    ReadGroundTruth(Existing(dir, fmt::format("Robot{}_Groundtruth.dat", n)), &robot);
    if (robot.odometry.empty() || robot.truth.empty()) {
      throw InputError(fmt::format("{}: robot {} has no odometry or no ground truth",
                                   dir.string(), n));
    }
    data.robots.push_back(std::move(robot));
  }
  return data;
}

}  // namespace slamkit
