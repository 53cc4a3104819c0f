#include "slamkit/io/writers.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <string>

#include "slamkit/io/atomic_file.hpp"

namespace slamkit {

// Doubles are printed with fmt's shortest representation that reads back to the same value
// ("{}"), so the files round-trip exactly and are byte-stable across platforms. TUM timestamps
// use fixed nanosecond precision, as the format's tools expect.

void WriteTumTrajectory(const std::filesystem::path& path, const Trajectory& trajectory) {
  std::string text;
  for (const StampedPose& p : trajectory) {
    const double half_yaw = 0.5 * p.pose.theta();
    fmt::format_to(std::back_inserter(text), "{:.9f} {} {} 0 0 0 {} {}\n", p.t_s, p.pose.x(),
                   p.pose.y(), std::sin(half_yaw), std::cos(half_yaw));
  }
  WriteFileAtomically(path, text);
}

void WritePoseText(const std::filesystem::path& path, const Trajectory& trajectory) {
  std::string text;
  for (const StampedPose& p : trajectory) {
    fmt::format_to(std::back_inserter(text), "{:.6f} {} {} {}\n", p.t_s, p.pose.x(), p.pose.y(),
                   p.pose.theta());
  }
  WriteFileAtomically(path, text);
}

void WriteLandmarkMapCsv(const std::filesystem::path& path, const LandmarkMap& map) {
  std::string text = "source_id,x_m,y_m,cov_xx,cov_xy,cov_yy\n";
  for (const MappedLandmark& l : map.landmarks) {
    fmt::format_to(std::back_inserter(text), "{},{},{},{},{},{}\n", l.source_id, l.position_m.x(),
                   l.position_m.y(), l.covariance(0, 0), l.covariance(0, 1), l.covariance(1, 1));
  }
  WriteFileAtomically(path, text);
}

void WriteLandmarkMapHistoryCsv(const std::filesystem::path& path,
                                const std::vector<LandmarkMapSnapshot>& history) {
  std::string text = "t_s,index,source_id,x_m,y_m,cov_xx,cov_xy,cov_yy\n";
  for (const LandmarkMapSnapshot& snapshot : history) {
    for (std::size_t i = 0; i < snapshot.map.landmarks.size(); ++i) {
      const MappedLandmark& l = snapshot.map.landmarks[i];
      fmt::format_to(std::back_inserter(text), "{:.6f},{},{},{},{},{},{},{}\n", snapshot.t_s, i,
                     l.source_id, l.position_m.x(), l.position_m.y(), l.covariance(0, 0),
                     l.covariance(0, 1), l.covariance(1, 1));
    }
  }
  WriteFileAtomically(path, text);
}

void WriteLandmarkWorldCsv(const std::filesystem::path& path, const LandmarkWorld& world) {
  std::string text = "id,x_m,y_m\n";
  for (const Landmark& l : world.landmarks) {
    fmt::format_to(std::back_inserter(text), "{},{},{}\n", l.id, l.position_m.x(),
                   l.position_m.y());
  }
  WriteFileAtomically(path, text);
}

void WriteJson(const std::filesystem::path& path, const nlohmann::json& json) {
  WriteFileAtomically(path, json.dump(2) + "\n");
}

}  // namespace slamkit
