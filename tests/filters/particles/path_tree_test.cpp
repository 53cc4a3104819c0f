#include "slamkit/filters/particles/path_tree.hpp"

#include <gtest/gtest.h>

#include "slamkit/filters/particles/particle_set.hpp"

namespace slamkit {
namespace {

TEST(PathTree, WalkGivesThePosesFromTheRoot) {
  PathTree path;
  EXPECT_TRUE(path.empty());
  EXPECT_TRUE(path.Walk().empty());
  for (int k = 0; k < 4; ++k) path.Append(10 * k, Pose2(k, 0, 0));
  const auto nodes = path.Walk();
  ASSERT_EQ(nodes.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(nodes[k]->step, 10 * k);
    EXPECT_EQ(nodes[k]->pose.x(), k);
  }
}

TEST(PathTree, CopiesShareTheirPathAndBranchOnAppend) {
  PathTree a;
  a.Append(0, Pose2(0, 0, 0));
  a.Append(1, Pose2(1, 0, 0));
  PathTree b = a;
  EXPECT_EQ(b.leaf(), a.leaf());
  b.Append(2, Pose2(2, 0, 0));
  EXPECT_EQ(a.Walk().size(), 2u);  // a is unchanged
  ASSERT_EQ(b.Walk().size(), 3u);
  EXPECT_EQ(b.leaf()->parent.get(), a.leaf());
}

// After resampling, the copies of one particle hold the very same nodes.
TEST(PathTree, ResamplingSharesPaths) {
  struct P {
    PathTree path;
  };
  ParticleSet<P> set(3, P{});
  for (int i = 0; i < 3; ++i) set[i].path.Append(0, Pose2(i, 0, 0));
  const PathTree::Node* kept = set[0].path.leaf();
  set.Keep(std::vector<int>{0, 0, 1});
  EXPECT_EQ(set[0].path.leaf(), kept);
  EXPECT_EQ(set[1].path.leaf(), kept);
  EXPECT_NE(set[2].path.leaf(), kept);
  set[1].path.Append(1, Pose2(5, 0, 0));
  EXPECT_EQ(set[1].path.leaf()->parent.get(), kept);
  EXPECT_EQ(set[0].path.leaf(), kept);
}

// A long path is freed without recursing once per node.
TEST(PathTree, FreesALongPath) {
  PathTree path;
  for (int k = 0; k < 300000; ++k) path.Append(k, Pose2());
  PathTree copy = path;
  copy.Append(-1, Pose2());
  path = PathTree();
  EXPECT_EQ(copy.Walk().size(), 300001u);
}

}  // namespace
}  // namespace slamkit
