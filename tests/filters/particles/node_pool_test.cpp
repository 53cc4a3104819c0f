#include "slamkit/filters/particles/node_pool.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <thread>
#include <vector>

namespace slamkit {
namespace {

struct alignas(32) Node {
  double values[5];
};
using Pool = NodePool<sizeof(Node), alignof(Node)>;

// Blocks alive together are distinct, aligned and do not overlap, across several slabs.
TEST(NodePool, LiveBlocksAreDistinctAndAligned) {
  std::vector<void*> live;
  for (int i = 0; i < 5000; ++i) live.push_back(Pool::Allocate());
  std::set<std::uintptr_t> addresses;
  for (void* p : live) {
    const auto a = reinterpret_cast<std::uintptr_t>(p);
    EXPECT_EQ(a % alignof(Node), 0u);
    addresses.insert(a);
  }
  ASSERT_EQ(addresses.size(), live.size());
  std::uintptr_t previous = 0;
  for (std::uintptr_t a : addresses) {
    if (previous != 0) {
      EXPECT_GE(a - previous, sizeof(Node));
    }
    previous = a;
  }
  for (void* p : live) Pool::Deallocate(p);
}

// The block freed last is the next one handed out on that thread: what keeps reuse in cache.
TEST(NodePool, ReusesTheBlockFreedLast) {
  if (!SLAMKIT_NODE_POOL_ENABLED) GTEST_SKIP() << "pool off under AddressSanitizer";
  void* a = Pool::Allocate();
  void* b = Pool::Allocate();
  Pool::Deallocate(a);
  EXPECT_EQ(Pool::Allocate(), a);
  Pool::Deallocate(a);
  Pool::Deallocate(b);
}

// One thread frees what others allocated (as resampling frees the nodes the update threads
// made): whole chains reach the depot and the allocating threads take them back instead of new
// slabs, and no block is ever handed to two owners.
TEST(NodePool, BlocksFreedByAnotherThreadComeBack) {
  if (!SLAMKIT_NODE_POOL_ENABLED) GTEST_SKIP() << "pool off under AddressSanitizer";
  constexpr int kBlocks = 8 * 1024;
  std::vector<void*> made(kBlocks);
  std::thread maker([&] {
    for (void*& p : made) p = Pool::Allocate();
  });
  maker.join();
  const std::set<void*> first(made.begin(), made.end());
  ASSERT_EQ(first.size(), made.size());
  std::thread freer([&] {
    for (void* p : made) Pool::Deallocate(p);
  });
  freer.join();  // its cache goes to the depot as it ends
  std::vector<void*> again(kBlocks);
  std::thread second([&] {
    for (void*& p : again) p = Pool::Allocate();
  });
  second.join();
  const std::set<void*> reused(again.begin(), again.end());
  ASSERT_EQ(reused.size(), again.size());
  int from_first = 0;
  for (void* p : again) from_first += first.count(p) ? 1 : 0;
  EXPECT_EQ(from_first, kBlocks);
  for (void* p : again) Pool::Deallocate(p);
}

}  // namespace
}  // namespace slamkit
