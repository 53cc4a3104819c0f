#include "slamkit/runners/grid/suite_merge.hpp"

#include <map>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "slamkit/runners/common/shard.hpp"

namespace slamkit {
namespace {

// "log/backend/seed": how a shard names each job of the study.
std::string JobName(const nlohmann::json& run) {
  return fmt::format("{}/{}/{}", run.at("log").get<std::string>(),
                     run.at("backend").get<std::string>(), run.at("seed").get<std::uint64_t>());
}

void CheckShard(const SavedSuiteShard& shard, const nlohmann::json& first,
                const std::string& first_name) {
  const nlohmann::json& s = shard.summary.at("shard");
  for (const char* key : {"count", "jobs", "study"}) {
    if (s.at(key) != first.at(key)) {
      throw InputError(fmt::format("{}: not a shard of the same study as {} ('shard.{}' differs)",
                                   shard.name, first_name, key));
    }
  }
  const int begin = s.at("first_job").get<int>(), end = s.at("end_job").get<int>();
  const nlohmann::json& runs = shard.summary.at("runs");
  bool matches = static_cast<int>(runs.size()) == end - begin;
  for (int i = 0; matches && i < end - begin; ++i) {
    matches = JobName(runs[i]) == s.at("jobs")[begin + i].get<std::string>();
  }
  if (!matches) {
    throw InputError(fmt::format("{}: its runs are not jobs {} to {} of the study", shard.name,
                                 begin, end - 1));
  }
}

}  // namespace

SuiteRunRecord SuiteRunRecordFromJson(const nlohmann::json& run) {
  SuiteRunRecord r;
  r.log = run.at("log").get<std::string>();
  r.backend = run.at("backend").get<std::string>();
  r.seed = run.at("seed").get<std::uint64_t>();
  r.exit_code = run.at("exit_code").get<int>();
  r.failure = run.at("failure").get<std::string>();
  r.wall_time_s = run.at("wall_time_s").get<double>();
  r.peak_rss_mib = run.at("peak_rss_mib").get<double>();
  r.metrics = run.at("metrics");
  return r;
}

MergedSuite MergeSuiteShards(const std::vector<SavedSuiteShard>& shards) {
  if (shards.empty()) throw InputError("merge: no shard folders");
  const nlohmann::json& first = shards.front().summary.at("shard");
  std::map<int, const SavedSuiteShard*> by_index;
  std::vector<std::pair<int, std::string>> indices;
  for (const SavedSuiteShard& shard : shards) {
    CheckShard(shard, first, shards.front().name);
    indices.emplace_back(shard.summary.at("shard").at("index").get<int>(), shard.name);
    by_index.emplace(indices.back().first, &shard);
  }
  CheckShardIndices(indices, first.at("count").get<int>());
  MergedSuite out;
  out.study = first.at("study");
  for (const auto& [index, shard] : by_index) {
    for (const nlohmann::json& run : shard->summary.at("runs")) {
      out.records.push_back(SuiteRunRecordFromJson(run));
    }
  }
  return out;
}

}  // namespace slamkit
