#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/fleet_log.hpp"
#include "slamkit/core/trajectory.hpp"

namespace slamkit {

// One robot of a UTIAS MRCLAM data set (Leung et al., IJRR 2011): its odometry, its sightings
// with the barcodes already mapped to subjects, and its motion-capture ground truth.
struct MrclamRobot {
  int subject = 0;  // 1 … N, as RobotN_*.dat
  struct Odometry {
    double t_s;
    double v_mps;
    double omega_radps;
  };
  struct Sighting {
    double t_s;
    int subject;  // a robot (1 … N) or a landmark (Landmark_Groundtruth.dat)
    double range_m;
    double bearing_rad;
  };
  std::vector<Odometry> odometry;
  std::vector<Sighting> sightings;
  Trajectory truth;
  // Sightings skipped because their barcode is not in Barcodes.dat (MRCLAM logs have some: the
  // barcode reader's misreads).
  int unknown_barcodes = 0;
};

struct MrclamDataset {
  std::vector<MrclamRobot> robots;            // Robot1 … RobotN, every one the folder has
  std::map<int, Eigen::Vector2d> landmarks;   // subject → surveyed position [m]
};

// Reads a folder of the MRCLAM layout: Barcodes.dat (subject, barcode), Landmark_Groundtruth.dat
// (subject, x, y, σx, σy) and, for N = 1, 2, … while they exist, RobotN_Odometry.dat (t, v, ω),
// RobotN_Measurement.dat (t, barcode, range, bearing) and RobotN_Groundtruth.dat (t, x, y, θ).
// Subjects 1 … N are the robots, the landmark file's subjects the landmarks. Throws InputError
// naming the file, line and field for a missing file, a wrong field count (a truncated line), a
// non-number or NaN/inf, a time earlier than the line before, a negative or absurd range
// (> 1000 m), a bearing beyond ±2π, a barcode mapped twice or a subject that is neither a robot
// nor a landmark; or naming the folder when it holds no Robot1 files.
MrclamDataset ReadMrclam(const std::filesystem::path& dir);

// Which part of a data set a cooperative run takes: a subset of the robots (subjects, in the
// order given; empty: all) and a window of [start_s, start_s + duration_s) after the first
// odometry record of those robots (no duration: to the end).
struct MrclamSelection {
  std::vector<int> robots;
  double start_s = 0.0;
  std::optional<double> duration_s;
};

// The selection as a fleet: vehicle k is selection.robots[k]; each odometry record becomes a
// control held until the robot's next record; sightings of landmarks keep the subject as their
// id, sightings of selected robots become vehicle sightings, sightings of robots left out are
// dropped. Start poses are the ground truth at the window's start (the latest sample at or
// before it), as SPEC S3 takes start poses as known. Throws InputError for a robot the data set
// does not have, a robot listed twice, or a window outside the recording.
std::pair<FleetLog, FleetTruth> MrclamFleet(const MrclamDataset& data,
                                            const MrclamSelection& selection);

}  // namespace slamkit
