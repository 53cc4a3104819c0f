#include "slamkit/runners/common/shard.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace slamkit {
namespace {

// The shards of a study cover every item once, in order, with sizes that differ by at most one.
TEST(Shard, PartsCoverEveryItemOnceInOrder) {
  for (int total : {1, 7, 10, 50, 1001}) {
    for (int count = 1; count <= std::min(total, 9); ++count) {
      int next = 0, smallest = total, largest = 0;
      for (int index = 1; index <= count; ++index) {
        const ShardRange range = RangeOfShard(total, {index, count});
        EXPECT_EQ(range.begin, next) << total << " " << index << "/" << count;
        next = range.end;
        smallest = std::min(smallest, range.size());
        largest = std::max(largest, range.size());
      }
      EXPECT_EQ(next, total);
      EXPECT_LE(largest - smallest, 1);
    }
  }
}

TEST(Shard, ParsesKOverNAndRejectsTheRest) {
  const Shard shard = ParseShard("3/4");
  EXPECT_EQ(shard.index, 3);
  EXPECT_EQ(shard.count, 4);
  for (const char* bad : {"", "3", "0/4", "5/4", "3/0", "a/4", "3/4x", "-1/4", "3/", "/4"}) {
    EXPECT_THROW(ParseShard(bad), std::invalid_argument) << bad;
  }
  EXPECT_THROW(RangeOfShard(3, {1, 4}), std::invalid_argument);  // more parts than items
}

}  // namespace
}  // namespace slamkit
