#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/runners/grid/suite_summary.hpp"

namespace slamkit {

// One `slamkit suite --shard K/N` output's summary.json, read.
struct SavedSuiteShard {
  std::string name;        // its folder, for messages
  nlohmann::json summary;  // summary.json
};

struct MergedSuite {
  std::vector<SuiteRunRecord> records;  // every run of the study, in the unsharded order
  nlohmann::json study;                 // what the shards ran (manifest, seeds, back end, ...)
};

// The run records of the shards joined in the unsharded suite's order, so that its summary
// (WriteSuiteSummary) is the unsharded one's, wall times and memory aside. Throws InputError
// naming the folder when a shard is missing, repeated, of another study (its `shard.study` or
// job list differs) or holds other runs than its range.
MergedSuite MergeSuiteShards(const std::vector<SavedSuiteShard>& shards);

// A run record as SuiteSummaryJson writes it, read back.
SuiteRunRecord SuiteRunRecordFromJson(const nlohmann::json& run);

}  // namespace slamkit
