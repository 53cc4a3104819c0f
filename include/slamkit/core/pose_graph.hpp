#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// A 2D pose graph as g2o (VERTEX_SE2, EDGE_SE2) and TORO (VERTEX2, EDGE2) files hold it.
struct PoseGraphVertex {
  int id = 0;  // the file's id; ids need not be contiguous or sorted
  Pose2 pose;  // the initial value
};

struct PoseGraphEdge {
  int from = 0;  // vertex ids: `measurement` is the pose of `to` in the frame of `from`
  int to = 0;
  Pose2 measurement;
  // Information (inverse covariance) of the measurement, in (x, y, θ) order, symmetric.
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

struct PoseGraph {
  std::vector<PoseGraphVertex> vertices;
  std::vector<PoseGraphEdge> edges;
};

}  // namespace slamkit
