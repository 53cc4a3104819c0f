#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/maps/landmark_map.hpp"

namespace slamkit {

// TUM RGB-D trajectory format: `t x y z qx qy qz qw` per line, z = 0, yaw as a quaternion about z.
void WriteTumTrajectory(const std::filesystem::path& path, const Trajectory& trajectory);
// One pose per line as `t x y theta` (t as in the source log, theta in radians).
void WritePoseText(const std::filesystem::path& path, const Trajectory& trajectory);
// Estimated landmarks as CSV: `source_id,x_m,y_m,cov_xx,cov_xy,cov_yy` with a header line.
void WriteLandmarkMapCsv(const std::filesystem::path& path, const LandmarkMap& map);
// Snapshots of a map over a run as CSV: `t_s,index,source_id,x_m,y_m,cov_xx,cov_xy,cov_yy`,
// one row per landmark of each snapshot (index: its place in that snapshot's map).
void WriteLandmarkMapHistoryCsv(const std::filesystem::path& path,
                                const std::vector<LandmarkMapSnapshot>& history);
// True landmarks as CSV: `id,x_m,y_m` with a header line (the format ReadLandmarkCsv reads).
void WriteLandmarkWorldCsv(const std::filesystem::path& path, const LandmarkWorld& world);
// Pretty-printed JSON, with doubles printed to round-trip exactly.
void WriteJson(const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace slamkit
