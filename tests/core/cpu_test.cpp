#include "slamkit/core/cpu.hpp"

#include <sched.h>

#include <thread>

#include <gtest/gtest.h>

namespace slamkit {
namespace {

// Issue 8, item 18: "all CPUs" is the affinity mask, not the machine. A thread pinned to one CPU
// must see 1 (hardware_concurrency would say every core the machine has).
TEST(UsableCpuCount, FollowsTheAffinityMaskOfTheCallingThread) {
  cpu_set_t mine;
  CPU_ZERO(&mine);
  ASSERT_EQ(sched_getaffinity(0, sizeof(mine), &mine), 0);
  EXPECT_EQ(UsableCpuCount(), CPU_COUNT(&mine));
  int first = 0;
  while (!CPU_ISSET(first, &mine)) ++first;
  int pinned_count = 0;
  std::thread pinned([&] {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    if (sched_setaffinity(0, sizeof(one), &one) == 0) pinned_count = UsableCpuCount();
  });
  pinned.join();
  EXPECT_EQ(pinned_count, 1);
}

}  // namespace
}  // namespace slamkit
