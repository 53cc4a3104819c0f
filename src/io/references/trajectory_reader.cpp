#include "slamkit/io/trajectory_reader.hpp"

#include <cmath>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "../text/text_records.hpp"

namespace slamkit {
namespace {

constexpr const char* kPlanarNames[] = {"t", "x", "y", "theta"};
constexpr const char* kTumNames[] = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};
// Larger than any building or campus, small enough that squares and alignment stay exact.
constexpr double kMaxMagnitude = 1e6;
constexpr double kUnitQuaternionTolerance = 1e-3;

// Field i: finite, and of magnitude at most kMaxMagnitude unless it is the time (field 0: Unix
// seconds are 1e9).
double Bounded(const text::Fields& fields, std::size_t i, const char* name) {
  const double value = fields.Number(i, {name});
  if (i > 0 && std::abs(value) > kMaxMagnitude) {
    fields.Fail({name}, fmt::format("magnitude above {:g} ('{}')", kMaxMagnitude, fields.Text(i)));
  }
  return value;
}

// A TUM line's pose: the rotation about z of a planar unit quaternion.
StampedPose ParseTum(const text::Fields& fields) {
  double v[std::size(kTumNames)];
  for (std::size_t i = 0; i < std::size(kTumNames); ++i) v[i] = Bounded(fields, i, kTumNames[i]);
  for (std::size_t i : {3, 4, 5}) {
    if (std::abs(v[i]) > text::kOutOfPlaneTolerance) {
      fields.Fail({kTumNames[i]}, fmt::format("must be 0 in a planar pose ('{}')", fields.Text(i)));
    }
  }
  const double norm = std::hypot(v[6], v[7]);
  if (std::abs(norm - 1.0) > kUnitQuaternionTolerance) {
    fields.Fail({"qw"}, fmt::format("(qz, qw) is not a unit quaternion (norm {:g})", norm));
  }
  return {v[0], Pose2(v[1], v[2], 2.0 * std::atan2(v[6], v[7]))};
}

StampedPose ParsePose(const text::Fields& fields) {
  if (fields.size() == std::size(kTumNames)) return ParseTum(fields);
  if (fields.size() != std::size(kPlanarNames)) {
    fields.Fail({"line"}, fmt::format("expected `t x y theta` (4 fields) or TUM `t x y z qx qy qz "
                                      "qw` (8 fields), got {} fields",
                                      fields.size()));
  }
  double v[std::size(kPlanarNames)];
  for (std::size_t i = 0; i < std::size(kPlanarNames); ++i) {
    v[i] = Bounded(fields, i, kPlanarNames[i]);
  }
  return {v[0], Pose2(v[1], v[2], v[3])};
}

}  // namespace

Trajectory ReadTrajectory(const std::filesystem::path& path) {
  Trajectory poses;
  text::ForEachRecord(path,
                      [&](const text::Fields& fields) { poses.push_back(ParsePose(fields)); });
  if (poses.empty()) {
    throw InputError(path.string() +
                     ": no poses (expected `t x y theta` or TUM `t x y z qx qy qz qw` lines)");
  }
  return poses;
}

}  // namespace slamkit
