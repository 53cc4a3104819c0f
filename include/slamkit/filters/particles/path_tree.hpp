#pragma once

#include <memory>
#include <vector>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// A particle's path as a leaf of a tree that all the particles share: each node holds one pose and
// a shared pointer to its parent. Copying a path (as resampling copies particles) shares all of
// its nodes; Append is O(1) and makes a new leaf; a node is freed once no path reaches it. Paths
// of different threads may be copied and appended concurrently (distinct PathTree objects).
class PathTree {
 public:
  struct Node {
    int step;  // what the pose belongs to (the filter's scan index, a time step)
    Pose2 pose;
    std::shared_ptr<Node> parent;
  };

  PathTree() = default;
  PathTree(const PathTree&) = default;
  PathTree(PathTree&&) noexcept = default;
  PathTree& operator=(const PathTree& other);
  PathTree& operator=(PathTree&& other) noexcept;
  ~PathTree();

  // Extends this path by one pose; other copies keep the path as it was.
  void Append(int step, const Pose2& pose);

  bool empty() const { return leaf_ == nullptr; }
  const Node* leaf() const { return leaf_.get(); }
  // The nodes from the root to the leaf.
  std::vector<const Node*> Walk() const;

 private:
  // Drops this path's hold on its nodes iteratively (a long chain would otherwise be freed by
  // recursion as deep as the path).
  void Release() noexcept;

  std::shared_ptr<Node> leaf_;
};

}  // namespace slamkit
