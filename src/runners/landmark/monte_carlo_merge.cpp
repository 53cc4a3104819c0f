#include "slamkit/runners/landmark/monte_carlo_merge.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "monte_carlo_batches.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/landmark/active_monte_carlo.hpp"
#include "slamkit/runners/landmark/active_outputs.hpp"
#include "slamkit/runners/landmark/outputs.hpp"

namespace slamkit {
namespace {

// The keys of metrics.json that a shard computes over its own runs only.
nlohmann::json WithoutAggregates(nlohmann::json metrics) {
  const nlohmann::json aggregates = MonteCarloResultJson(MonteCarloResult{});
  for (const auto& [key, unused] : aggregates.items()) metrics.erase(key);
  metrics.erase("sections");
  metrics.erase("shard");
  return metrics;
}

// The first key whose value differs between two metrics objects.
std::string FirstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  for (const auto& [key, value] : a.items()) {
    if (!b.contains(key) || b.at(key) != value) return key;
  }
  for (const auto& [key, unused] : b.items()) {
    if (!a.contains(key)) return key;
  }
  return "";
}

RunRecord RecordOfSaved(const SavedMonteCarloRun& run) {
  const nlohmann::json& e = run.entry;
  RunRecord r;
  r.t_s = run.errors.t_s;
  r.errors = run.errors.errors;
  r.nees = run.errors.nees;
  r.rmse = {e.at("position_rmse_m").get<double>(), e.at("heading_rmse_rad").get<double>()};
  r.landmarks_mapped = e.at("landmarks_mapped").get<std::size_t>();
  r.map_rmse_m = e.at("map_rmse_m").get<double>();
  const nlohmann::json& a = e.at("association");
  r.association = {a.at("sightings").get<int>(), a.at("matched").get<int>(),
                   a.at("correct").get<int>(),   a.at("matchable").get<int>(),
                   a.at("created").get<int>(),   a.at("dropped").get<int>()};
  r.steps_timed = r.nees.size();
  r.step_time_sum_s = e.at("step_time_mean_s").get<double>() * static_cast<double>(r.steps_timed);
  r.step_time_max_s = e.at("step_time_max_s").get<double>();
  return r;
}

std::vector<SectionStats> SectionsOfSaved(const nlohmann::json& entry) {
  std::vector<SectionStats> sections;
  for (const nlohmann::json& s : entry.at("sections")) {
    SectionStats stats;
    stats.periods = s.at("periods").get<int>();
    stats.observations = s.at("observations").get<int>();
    stats.landmarks = s.at("landmarks").get<int>();
    stats.observations_per_period = s.at("observations_per_period").get<double>();
    stats.observations_per_landmark = s.at("observations_per_landmark").get<double>();
    sections.push_back(stats);
  }
  return sections;
}

// The shards by index, each checked to be one part of the same study as the first.
std::map<int, const SavedMonteCarloShard*> CheckedShards(
    const std::vector<SavedMonteCarloShard>& shards) {
  if (shards.empty()) throw InputError("merge: no shard folders");
  const nlohmann::json study = WithoutAggregates(shards.front().metrics);
  const int count = shards.front().metrics.at("shard").at("count").get<int>();
  std::map<int, const SavedMonteCarloShard*> by_index;
  std::vector<std::pair<int, std::string>> indices;
  for (const SavedMonteCarloShard& shard : shards) {
    const nlohmann::json& s = shard.metrics.at("shard");
    const std::string differs = FirstDifference(study, WithoutAggregates(shard.metrics));
    if (!differs.empty() || s.at("count").get<int>() != count) {
      throw InputError(fmt::format("{}: not a shard of the same study as {} ('{}' differs)",
                                   shard.name, shards.front().name,
                                   differs.empty() ? "shard.count" : differs));
    }
    indices.emplace_back(s.at("index").get<int>(), shard.name);
    by_index.emplace(indices.back().first, &shard);
    const int first = s.at("first_run").get<int>(), end = s.at("end_run").get<int>();
    bool in_order = static_cast<int>(shard.runs.size()) == end - first;
    for (std::size_t i = 0; in_order && i < shard.runs.size(); ++i) {
      in_order = shard.runs[i].entry.at("run").get<int>() == first + static_cast<int>(i);
    }
    if (!in_order) {
      throw InputError(fmt::format("{}: its runs are not runs {} to {}", shard.name, first, end - 1));
    }
  }
  CheckShardIndices(indices, count);
  return by_index;
}

}  // namespace

MergedMonteCarlo MergeMonteCarloShards(const std::vector<SavedMonteCarloShard>& shards,
                                       LandmarkWorld world) {
  const std::map<int, const SavedMonteCarloShard*> by_index = CheckedShards(shards);
  MergedMonteCarlo out;
  out.mc.world = std::move(world);
  const int runs = shards.front().metrics.at("runs").get<int>();
  internal::RunAggregator aggregate(out.mc, runs);
  std::vector<std::vector<SectionStats>> sections;
  const bool has_sections = shards.front().metrics.contains("sections");
  for (const auto& [index, shard] : by_index) {
    for (const SavedMonteCarloRun& run : shard->runs) {
      aggregate.Add(RecordOfSaved(run));
      if (has_sections) sections.push_back(SectionsOfSaved(run.entry));
      out.per_run.push_back(run.entry);
    }
  }
  aggregate.Finish();
  out.metrics = shards.front().metrics;
  out.metrics.erase("shard");
  out.metrics.update(MonteCarloResultJson(out.mc));
  if (has_sections) out.metrics["sections"] = SectionMeansJson(MeanSections(sections));
  return out;
}

}  // namespace slamkit
