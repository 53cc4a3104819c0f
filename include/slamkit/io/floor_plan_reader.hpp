#pragma once

#include <filesystem>

#include "slamkit/maps/walls.hpp"

namespace slamkit {

// Reads a floor plan described by its walls, in metres, one item per line:
//   x1 y1 x2 y2                     one wall from (x1, y1) to (x2, y2)
//   poly x1 y1 x2 y2 x3 y3 ...      a closed polygon: a wall between consecutive points and one
//                                   from the last point back to the first (at least 3 points;
//                                   do not repeat the first point at the end)
// Fields are separated by spaces or tabs; `#` starts a comment that runs to the end of the line;
// blank lines are ignored. The walls come in file order, a polygon's from point 1 onwards.
// Throws InputError naming the file, the line and the field (`x2`, `poly` `y3`, ...) for a wrong
// count of numbers, a non-number, NaN or inf, a zero-length wall (a polygon's consecutive points
// too), a polygon of fewer than 3 points; and naming the file when it has no walls at all.
Walls ReadFloorPlanFile(const std::filesystem::path& path);

}  // namespace slamkit
