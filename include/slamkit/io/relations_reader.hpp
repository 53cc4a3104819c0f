#pragma once

#include <filesystem>
#include <vector>

#include "slamkit/core/relation.hpp"

namespace slamkit {

// Reads `t1 t2 x y z roll pitch yaw` lines (z, roll and pitch must be 0 for a 2D log within
// 1e-6), delta = (x, y, yaw); blank and `#` lines are ignored, gzip is read transparently. Throws
// InputError naming the file, line and field (a wrong field count, a non-number, NaN/inf).
std::vector<PoseRelation> ReadRelations(const std::filesystem::path& path);

}  // namespace slamkit
