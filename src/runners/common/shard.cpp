#include "slamkit/runners/common/shard.hpp"

#include <charconv>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"

namespace slamkit {

ShardRange RangeOfShard(int total, const Shard& shard) {
  if (shard.count < 1 || shard.index < 1 || shard.index > shard.count || shard.count > total) {
    throw std::invalid_argument("shard " + std::to_string(shard.index) + "/" +
                                std::to_string(shard.count) + " of " + std::to_string(total) +
                                " items: need 1 <= K <= N <= " + std::to_string(total));
  }
  // 64 bits: total × index may pass 2^31 for a large study.
  const auto at = [&](int i) {
    return static_cast<int>(static_cast<long long>(total) * i / shard.count);
  };
  return {at(shard.index - 1), at(shard.index)};
}

void CheckShardIndices(const std::vector<std::pair<int, std::string>>& given, int count) {
  std::set<int> seen;
  for (const auto& [index, folder] : given) {
    if (!seen.insert(index).second) {
      throw InputError(fmt::format("{}: shard {}/{} given twice", folder, index, count));
    }
  }
  for (int index = 1; index <= count; ++index) {
    if (!seen.count(index)) {
      throw InputError(fmt::format("merge: shard {}/{} is missing", index, count));
    }
  }
}

Shard ParseShard(const std::string& text) {
  const auto slash = text.find('/');
  Shard shard;
  const auto number = [&](std::size_t from, std::size_t to, int& out) {
    const char* first = text.data() + from;
    const char* last = text.data() + to;
    const auto [end, error] = std::from_chars(first, last, out);
    return from < to && error == std::errc() && end == last;
  };
  if (slash == std::string::npos || !number(0, slash, shard.index) ||
      !number(slash + 1, text.size(), shard.count) || shard.count < 1 || shard.index < 1 ||
      shard.index > shard.count) {
    throw std::invalid_argument("'" + text + "' is not a shard K/N with 1 <= K <= N (e.g. 2/4)");
  }
  return shard;
}

}  // namespace slamkit
