#pragma once

#include <string>
#include <utility>
#include <vector>

namespace slamkit {

// One of `count` parts of a study (`--shard index/count`, 1-based as a Slurm job array's
// indices usually are): each part runs a contiguous range of the study's items (Monte Carlo runs,
// a suite's log × seed pairs), and the parts together run each item exactly once.
struct Shard {
  int index = 1;
  int count = 1;
  bool whole() const { return count == 1; }
};

// Items [begin, end) of the study.
struct ShardRange {
  int begin = 0;
  int end = 0;
  int size() const { return end - begin; }
};

// Shard `shard`'s items of `total`: contiguous, the sizes differing by at most one. Throws
// std::invalid_argument unless 1 <= index <= count <= total.
ShardRange RangeOfShard(int total, const Shard& shard);

// That the indices of the shard outputs given (each with its folder, for the message) are 1 ..
// `count`, each once: InputError naming the folder of an index given twice, or the missing
// index.
void CheckShardIndices(const std::vector<std::pair<int, std::string>>& given, int count);

// "3/4" -> {3, 4}; std::invalid_argument with a message naming `text` otherwise.
Shard ParseShard(const std::string& text);

}  // namespace slamkit
