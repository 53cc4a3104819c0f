#pragma once

#include <filesystem>

#include "slamkit/core/trajectory.hpp"

namespace slamkit {

// Reads a per-scan trajectory, such as a reference of corrected poses, one pose per line in
// either of two layouts, told apart by the field count:
//   `t x y theta`                 (4 fields: the suite's NAME.reference.txt),
//   `t x y z qx qy qz qw`         (8 fields: TUM, as `slamkit grid` writes and evo reads; the pose
//                                  must be planar: z, qx and qy zero up to 1e-6, |q| = 1 up to 1e-3).
// Blank and `#` lines are ignored, gzip is read transparently, poses keep the file's order (times
// may repeat or be all zero: pairing by index is then the caller's choice). Throws InputError
// naming the file, line and field (a wrong field count, a non-number, NaN/inf, a coordinate or angle above 1e6, a
// non-planar pose) or saying what it expected when the file holds no pose.
Trajectory ReadTrajectory(const std::filesystem::path& path);

}  // namespace slamkit
