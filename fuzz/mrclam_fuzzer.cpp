// ReadMrclam and MrclamFleet on a folder written from one input: sections headed by a line
// `=== NAME` become the files NAME (Barcodes.dat, Landmark_Groundtruth.dat, RobotN_*.dat).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/mrclam_reader.hpp"

namespace {

// Writes the sections of `text` into a fresh folder; names are kept to plain file names.
std::filesystem::path WriteFolder(std::string_view text) {
  const std::filesystem::path dir = slamkit::fuzz::ScratchDir() / "mrclam";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string name;
  std::string body;
  const auto flush = [&] {
    if (!name.empty()) slamkit::fuzz::WriteFile("mrclam/" + name, body);
    body.clear();
  };
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    if (line.starts_with("=== ")) {
      flush();
      name = std::string(line.substr(4));
      // Plain file names only ([A-Za-z0-9_.], not "." or ".."): the harness's own limit.
      const bool plain = std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
      });
      if (!plain || name.empty() || name == "." || name == ".." || name.size() > 64) name.clear();
    } else {
      body.append(line).push_back('\n');
    }
    start = end + 1;
  }
  flush();
  return dir;
}

}  // namespace

int slamkit::fuzz::FuzzMrclam(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const slamkit::MrclamDataset dataset =
        slamkit::ReadMrclam(WriteFolder(AsText(data, size)));
    Check(!dataset.robots.empty(), "a data set has a robot");
    for (const slamkit::MrclamRobot& r : dataset.robots) {
      Check(!r.odometry.empty() && !r.truth.empty(), "every robot has odometry and truth");
      for (const auto& s : r.sightings) {
        Check(std::isfinite(s.range_m) && s.range_m >= 0.0, "ranges are finite, >= 0");
        Check(std::abs(s.bearing_rad) <= 3.15, "bearings are wrapped");
      }
    }
    const auto [log, truth] = slamkit::MrclamFleet(dataset, {});
    Check(log.vehicles == static_cast<int>(dataset.robots.size()), "every robot is a vehicle");
    for (std::size_t i = 1; i < log.events.size(); ++i) {
      Check(log.events[i - 1].t_s <= log.events[i].t_s, "events are in time order");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
