#include "slamkit/filters/fastslam/landmark_tree.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

namespace slamkit {
namespace {

using Tree = LandmarkTree<double>;

std::size_t DistinctBytes(std::initializer_list<const Tree*> trees) {
  const std::vector<const Tree*> v(trees);
  return Tree::CountDistinctNodes(v).bytes();
}

TEST(LandmarkTree, InsertsAndFindsTenThousandLandmarksInAnyOrder) {
  const int n = 10000;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  Rng rng(3);
  for (int i = n - 1; i > 0; --i) {
    std::swap(order[i], order[static_cast<int>(rng.Uniform(0.0, i + 1.0 - 1e-9))]);
  }
  Tree tree;
  for (int i : order) tree.Set(i, 0.5 * i);
  EXPECT_EQ(tree.size(), n);
  EXPECT_EQ(tree.levels(), 14);  // 2^14 = 16384 ≥ 10^4 > 2^13: balanced by construction
  for (int i = 0; i < n; ++i) {
    ASSERT_NE(tree.Get(i), nullptr) << i;
    EXPECT_EQ(*tree.Get(i), 0.5 * i);
  }
  EXPECT_EQ(tree.Get(n), nullptr);
  EXPECT_EQ(tree.Get(-1), nullptr);
  int expected = 0;
  tree.ForEach([&](int index, double value) {
    EXPECT_EQ(index, expected++);
    EXPECT_EQ(value, 0.5 * index);
  });
  EXPECT_EQ(expected, n);
  const Tree::NodeCount count = Tree::CountDistinctNodes(std::vector<const Tree*>{&tree});
  EXPECT_EQ(count.leaves, std::size_t(n));
  // Each level has at most half the nodes of the one below, rounded up: no more than n + levels.
  EXPECT_LE(count.branches, std::size_t(n + tree.levels()));
}

TEST(LandmarkTree, ChangingOneCopyNeverChangesAnother) {
  Tree original;
  for (int i = 0; i < 1000; ++i) original.Set(i, i);
  Tree changed = original;
  const Tree untouched = original;
  Rng rng(5);
  std::vector<double> expected(1000);
  std::iota(expected.begin(), expected.end(), 0.0);
  for (int k = 0; k < 300; ++k) {
    const int i = static_cast<int>(rng.Uniform(0.0, 999.999));
    if (k % 3 == 0) {
      changed.Erase(i);
      expected[i] = -1.0;
    } else {
      changed.Set(i, -2.0 - k);
      expected[i] = -2.0 - k;
    }
  }
  changed.Set(5000, 7.0);  // grows this copy by three levels; the others keep theirs
  for (int i = 0; i < 1000; ++i) {
    ASSERT_NE(original.Get(i), nullptr);
    EXPECT_EQ(*original.Get(i), i);
    EXPECT_EQ(*untouched.Get(i), i);
    if (expected[i] == -1.0) {
      EXPECT_EQ(changed.Get(i), nullptr) << i;
    } else {
      EXPECT_EQ(*changed.Get(i), expected[i]) << i;
    }
  }
  EXPECT_EQ(original.Get(5000), nullptr);
  EXPECT_EQ(original.levels(), 10);
  EXPECT_EQ(original.size(), 1000);
}

TEST(LandmarkTree, CopySharesEveryNodeAndAChangeCopiesOnlyItsPath) {
  Tree a;
  for (int i = 0; i < 4096; ++i) a.Set(i, i);
  const std::size_t one = DistinctBytes({&a});
  Tree b = a;
  EXPECT_EQ(DistinctBytes({&a, &b}), one);  // O(1) copy: nothing duplicated
  b.Set(1234, -1.0);
  const Tree::NodeCount both = Tree::CountDistinctNodes(std::vector<const Tree*>{&a, &b});
  const Tree::NodeCount alone = Tree::CountDistinctNodes(std::vector<const Tree*>{&a});
  EXPECT_EQ(both.leaves, alone.leaves + 1);
  EXPECT_EQ(both.branches, alone.branches + std::size_t(a.levels()));  // the path, log₂ 4096
}

TEST(LandmarkTree, ErasingEverythingFreesEveryBranch) {
  Tree tree;
  for (int i = 0; i < 100; ++i) tree.Set(i, i);
  for (int i = 99; i >= 0; --i) tree.Erase(i);
  tree.Erase(3);  // absent: no change
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(DistinctBytes({&tree}), 0u);
  EXPECT_THROW(tree.Set(-1, 0.0), std::out_of_range);
}

}  // namespace
}  // namespace slamkit
