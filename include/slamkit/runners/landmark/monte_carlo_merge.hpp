#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/io/run_errors_reader.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"

namespace slamkit {

// One run as a `slamkit mc --shard K/N` output keeps it.
struct SavedMonteCarloRun {
  nlohmann::json entry;  // its per_run entry of metrics.json
  RunErrorsCsv errors;   // its run_K/errors.csv
};

// One shard's output folder, read.
struct SavedMonteCarloShard {
  std::string name;         // the folder, for messages
  nlohmann::json metrics;   // metrics.json without per_run
  std::vector<SavedMonteCarloRun> runs;  // in index order
};

struct MergedMonteCarlo {
  nlohmann::json metrics;               // the unsharded run's metrics.json without per_run
  std::vector<nlohmann::json> per_run;  // in index order
  MonteCarloResult mc;                  // its aggregates and `world` (no runs kept)
};

// The unsharded study from its N shards, given in any order: every run replayed through the
// aggregation of RunMonteCarlo in index order, so that every figure equals the unsharded run's
// bit for bit except the step times (a run's saved mean and maximum stand for its steps).
// Throws InputError naming the folder when a shard is missing, repeated, of another study (a key
// of metrics.json other than the aggregates differs: the key is named) or holds other runs than
// its range.
MergedMonteCarlo MergeMonteCarloShards(const std::vector<SavedMonteCarloShard>& shards,
                                       LandmarkWorld world);

}  // namespace slamkit
