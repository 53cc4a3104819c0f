#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <unordered_set>
#include <utility>

#include "slamkit/filters/particles/node_pool.hpp"

namespace slamkit {

// A persistent map from landmark index to `T`: FastSLAM's balanced landmark tree shared between
// particles (Montemerlo et al. 2002, FastSLAM, Sec. 4.2 "Efficient implementation"). Copying a tree
// (as resampling copies a particle) is O(1) and shares every node; Set and Erase copy the O(log N)
// nodes on the path to the index (path copying), so a change is seen by this copy only.
//
// Why a complete binary tree over the indices 0..capacity-1 rather than an AVL tree or a treap: a
// filter hands out landmark indices densely and in increasing order, so the index's bits are the
// path from the root. The tree is balanced by construction (depth ⌈log₂ capacity⌉, no rotations,
// no keys stored), grows by adding a root level above the old root when an index reaches the
// capacity, and a change copies exactly depth + 1 nodes. Empty subtrees are null pointers, so a
// sparse tree costs only the paths to its entries.
//
// Nodes are immutable once shared (std::shared_ptr<const …>), so distinct trees may be read,
// copied and changed from different threads at once. Freeing recurses only as deep as the tree
// (about 17 levels for 10^5 landmarks).
template <class T>
class LandmarkTree {
 public:
  LandmarkTree() = default;

  // The value at `index`, or nullptr when the tree holds none. O(log capacity).
  const T* Get(int index) const {
    if (index < 0 || index >= capacity()) return nullptr;
    const NodeBase* node = root_.get();
    for (int level = levels_; level > 0 && node != nullptr; --level) {
      node = static_cast<const Branch*>(node)->children[Bit(index, level)].get();
    }
    return node == nullptr ? nullptr : &static_cast<const Leaf*>(node)->value;
  }

  // Stores `value` at `index` (≥ 0), copying the path to it; other copies keep their value.
  void Set(int index, T value) {
    if (index < 0) throw std::out_of_range("LandmarkTree::Set: negative index");
    while (index >= capacity()) Grow();
    bool added = false;
    root_ = SetIn(root_, levels_, index, std::move(value), added);
    if (added) ++size_;
  }

  // Removes the value at `index`, if any, copying the path to it; other copies keep it.
  void Erase(int index) {
    if (Get(index) == nullptr) return;
    root_ = EraseIn(root_, levels_, index);
    --size_;
  }

  // Calls f(index, value) for every stored value in increasing index order.
  template <class F>
  void ForEach(F&& f) const {
    Visit(root_.get(), levels_, 0, f);
  }

  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Indices below this are reachable without growing.
  int capacity() const { return 1 << levels_; }
  int levels() const { return levels_; }

  // Bytes of one leaf and of one branch as allocated by std::allocate_shared (the node beside its
  // control block: a vtable pointer and two counts), for memory accounting.
  static constexpr std::size_t LeafBytes() { return sizeof(Leaf) + kControlBlockBytes; }
  static constexpr std::size_t BranchBytes() { return sizeof(Branch) + kControlBlockBytes; }

  // The distinct leaves and branches reachable from `trees` (a node shared by several trees, or
  // several times, counts once): what a particle set holds in memory. O(distinct nodes).
  struct NodeCount {
    std::size_t leaves = 0;
    std::size_t branches = 0;
    std::size_t bytes() const { return leaves * LeafBytes() + branches * BranchBytes(); }
  };
  static NodeCount CountDistinctNodes(std::span<const LandmarkTree* const> trees) {
    NodeCount count;
    std::unordered_set<const void*> seen;
    for (const LandmarkTree* tree : trees) CountIn(tree->root_.get(), tree->levels_, seen, count);
    return count;
  }

 private:
  static constexpr std::size_t kControlBlockBytes = sizeof(void*) + 2 * sizeof(int);

  // Leaves and branches share no virtual base: a node's kind follows from its level, and
  // std::allocate_shared records the right deleter for each.
  struct NodeBase {};
  using NodePtr = std::shared_ptr<const NodeBase>;
  struct Branch : NodeBase {
    NodePtr children[2];
  };
  struct Leaf : NodeBase {
    explicit Leaf(T v) : value(std::move(v)) {}
    T value;
  };

  // Nodes come from NodePool: a step of a particle filter allocates and frees thousands.
  template <class Node, class... Args>
  static std::shared_ptr<Node> MakeNode(Args&&... args) {
    return std::allocate_shared<Node>(NodePoolAllocator<Node>(), std::forward<Args>(args)...);
  }

  // The child taken at `level` (levels_ at the root, 1 just above the leaves).
  static int Bit(int index, int level) { return (index >> (level - 1)) & 1; }

  void Grow() {
    if (levels_ >= 30) throw std::length_error("LandmarkTree: more than 2^30 indices");
    if (root_ != nullptr) {
      auto root = MakeNode<Branch>();
      root->children[0] = std::move(root_);
      root_ = std::move(root);
    }
    ++levels_;
  }

  static NodePtr SetIn(const NodePtr& node, int level, int index, T&& value, bool& added) {
    if (level == 0) {
      added = node == nullptr;
      return MakeNode<Leaf>(std::move(value));
    }
    auto copy = node ? MakeNode<Branch>(*static_cast<const Branch*>(node.get()))
                     : MakeNode<Branch>();
    NodePtr& child = copy->children[Bit(index, level)];
    child = SetIn(child, level - 1, index, std::move(value), added);
    return copy;
  }

  // Only called on a path that holds a value at `index`. Drops branches left empty.
  static NodePtr EraseIn(const NodePtr& node, int level, int index) {
    if (level == 0) return nullptr;
    auto copy = MakeNode<Branch>(*static_cast<const Branch*>(node.get()));
    NodePtr& child = copy->children[Bit(index, level)];
    child = EraseIn(child, level - 1, index);
    if (copy->children[0] == nullptr && copy->children[1] == nullptr) return nullptr;
    return copy;
  }

  template <class F>
  static void Visit(const NodeBase* node, int level, int first, F& f) {
    if (node == nullptr) return;
    if (level == 0) {
      f(first, static_cast<const Leaf*>(node)->value);
      return;
    }
    const auto* branch = static_cast<const Branch*>(node);
    Visit(branch->children[0].get(), level - 1, first, f);
    Visit(branch->children[1].get(), level - 1, first + (1 << (level - 1)), f);
  }

  static void CountIn(const NodeBase* node, int level, std::unordered_set<const void*>& seen,
                      NodeCount& count) {
    if (node == nullptr || !seen.insert(node).second) return;
    if (level == 0) {
      ++count.leaves;
      return;
    }
    ++count.branches;
    const auto* branch = static_cast<const Branch*>(node);
    CountIn(branch->children[0].get(), level - 1, seen, count);
    CountIn(branch->children[1].get(), level - 1, seen, count);
  }

  NodePtr root_;
  int levels_ = 0;  // capacity 2^levels_; a lone leaf at the root when 0
  int size_ = 0;
};

}  // namespace slamkit
