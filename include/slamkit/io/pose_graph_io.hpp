#pragma once

#include <filesystem>

#include "slamkit/core/pose_graph.hpp"

namespace slamkit {

// Reads a 2D pose graph in g2o or TORO format, or a mix of the two: each line's format is that of
// its tag. Blank lines and lines starting with `#` are skipped; gzip is read transparently.
//   g2o:  VERTEX_SE2 id x y theta
//         EDGE_SE2 id1 id2 dx dy dtheta I11 I12 I13 I22 I23 I33
//   TORO: VERTEX2 id x y theta
//         EDGE2 id1 id2 dx dy dtheta I11 I12 I22 I33 I13 I23
// (dx, dy, dtheta) is the pose of id2 in the frame of id1 [m, m, rad]; the I entries are the
// information matrix in (x, y, θ) order: g2o lists its upper triangle row by row, TORO lists
// xx, xy, yy, θθ, xθ, yθ. Ids are any int. `FIX id...` (g2o: hold these vertices) and
// `EQUIV id1 id2` (TORO: two vertices are the same place) are checked for integer ids and ignored:
// PoseGraph cannot express them (the edges of w100.graph already join each EQUIV pair).
//
// Vertices keep the order of their VERTEX lines, edges that of their EDGE lines, wherever the
// lines are in the file. A file without any VERTEX line (CSAIL.g2o, manhattan.g2o, w20000.txt)
// gets one vertex per id that its edges name, with the identity pose, in increasing id order. In
// a file with VERTEX lines, every id an edge names must have one, else the edge's line is in
// error: an initial value is either given for all vertices or for none.
//
// Throws InputError naming the file, the line and the field (`file:line: TAG field 'name':
// reason`) for an unknown tag, a missing or extra field, a field that is not a number (or an
// integer, for ids), NaN or inf, a duplicate vertex id, an edge from a vertex to itself, an
// information matrix that is not symmetric positive definite once its lower triangle is filled
// from the upper one, a file with neither vertex nor edge, and a file that is not text (a control
// byte other than tab or CR). The numbers are not bounded beyond being finite.
PoseGraph ReadPoseGraph(const std::filesystem::path& path);

// Writes `graph` in g2o format: a VERTEX_SE2 line per vertex, then an EDGE_SE2 line per edge, in
// the graph's order, every number with 17 significant digits, so that ReadPoseGraph gives back
// the same graph to the bit (the upper triangle of each information matrix is written, so it must
// be symmetric). The file is written under a temporary name and renamed into place; throws
// std::runtime_error naming the path when the write fails.
void WritePoseGraphG2o(const std::filesystem::path& path, const PoseGraph& graph);

}  // namespace slamkit
