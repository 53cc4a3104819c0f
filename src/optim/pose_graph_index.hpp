// Vertex ids to indices (private to optim).
#pragma once

#include <stdexcept>
#include <string>
#include <unordered_map>

#include "slamkit/core/pose_graph.hpp"

namespace slamkit::internal {

class VertexIndex {
 public:
  explicit VertexIndex(const PoseGraph& graph) {
    for (std::size_t i = 0; i < graph.vertices.size(); ++i) {
      if (!index_.emplace(graph.vertices[i].id, static_cast<int>(i)).second) {
        throw std::invalid_argument("pose graph: vertex " + std::to_string(graph.vertices[i].id) +
                                    " appears twice");
      }
    }
  }
  int operator()(int id) const {
    const auto it = index_.find(id);
    if (it == index_.end()) {
      throw std::invalid_argument("pose graph: an edge names vertex " + std::to_string(id) +
                                  ", which the graph does not have");
    }
    return it->second;
  }

 private:
  std::unordered_map<int, int> index_;
};

}  // namespace slamkit::internal
