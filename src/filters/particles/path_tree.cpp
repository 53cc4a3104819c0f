#include "slamkit/filters/particles/path_tree.hpp"

#include <algorithm>
#include <utility>

namespace slamkit {

PathTree& PathTree::operator=(const PathTree& other) {
  if (this != &other) {
    std::shared_ptr<Node> keep = other.leaf_;
    Release();
    leaf_ = std::move(keep);
  }
  return *this;
}

PathTree& PathTree::operator=(PathTree&& other) noexcept {
  if (this != &other) {
    Release();
    leaf_ = std::move(other.leaf_);
  }
  return *this;
}

PathTree::~PathTree() { Release(); }

void PathTree::Release() noexcept {
  std::shared_ptr<Node> node = std::move(leaf_);
  // While this path is a node's only holder, detach its parent before freeing it. (A count read as
  // more than one may drop to one meanwhile in another thread: the node is then freed by the
  // ordinary recursive release, which is correct, only deeper.)
  while (node && node.use_count() == 1) node = std::move(node->parent);
}

void PathTree::Append(int step, const Pose2& pose) {
  leaf_ = std::make_shared<Node>(Node{step, pose, std::move(leaf_)});
}

std::vector<const PathTree::Node*> PathTree::Walk() const {
  std::vector<const Node*> nodes;
  for (const Node* n = leaf_.get(); n != nullptr; n = n->parent.get()) nodes.push_back(n);
  std::reverse(nodes.begin(), nodes.end());
  return nodes;
}

}  // namespace slamkit
