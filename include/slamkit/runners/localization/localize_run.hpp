#pragma once

// Monte Carlo localisation over a CARMEN log on a saved map (issue 31): the filter
// (filters/localization), its parameters' table, the run and its metrics.json.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/filters/localization/map_scan_refiner.hpp"
#include "slamkit/filters/localization/monte_carlo_localization.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/io/param_table.hpp"
#include "slamkit/maps/likelihood_field.hpp"

namespace slamkit {

// The filter's parameters as the localiser runs it: MclParams' (AMCL's) with augmented MCL's
// random particles on (0.001, 0.1), since the refiner tells the localiser when they may come.
MclParams LocalizerMclParams();

struct LocalizationConfig {
  MclParams mcl = LocalizerMclParams();
  LikelihoodFieldParams field;
  MapScanRefinerParams refine = DefaultRefinerParams();
  // Random particles only after this many scans in a row whose pose the refiner could not match
  // to the map: where the map merely fails to explain some beams (people, doors) the scans still
  // match and the estimate stays put; a robot carried away matches nowhere near its estimate.
  int recovery_after_unmatched_scans = 10;
};

// Every key of LocalizationConfig: the YAML reader, metrics.json's echo and the command line's
// flags walk it.
config::ParamTable LocalizationParamTable(LocalizationConfig& config);
// `defaults` with the keys a YAML file gives; InputError naming the file, line and key.
LocalizationConfig LoadLocalizationConfig(const std::filesystem::path& path,
                                          const LocalizationConfig& defaults = {});

struct LocalizationResult {
  Trajectory trajectory;  // one pose per scan, in the map's frame
  int scans = 0;
  int updates = 0;
  // The first scan after which the filter stayed converged (spread below converged_spread_m)
  // and drew no random particle to the end of the log (unset: it never settled); and the first
  // scan where it was converged at all.
  std::optional<int> settled_scan;
  std::optional<int> first_converged_scan;
  double mean_particles = 0.0;  // over the updates
  int most_particles = 0;
  int refined_scans = 0;  // scans whose pose the map match sharpened
  // Updates that drew random particles (augmented MCL, when on: the filter found the scans
  // unlikely, as when the robot is carried away) and the scan of the last one.
  int recovery_updates = 0;
  std::optional<int> last_recovery_scan;
  double wall_time_s = 0.0;
};

// The filter over every scan of `log` on the saved `map`, started at `initial_pose` (in the map's
// frame) or, when unset, globally; each scan's pose is then refined against the map once the
// filter has converged (config.refine). `progress(done, total)` is called every few scans.
LocalizationResult RunLocalization(const CarmenLog& log, const OccupancyImage& map,
                                   const LocalizationConfig& config,
                                   const std::optional<Pose2>& initial_pose,
                                   const std::function<void(int, int)>& progress = {});

// metrics.json of a localisation run; `relations` and `reference` may be null.
nlohmann::json LocalizationMetrics(const LocalizationResult& result,
                                   const LocalizationConfig& config,
                                   const RelationErrorStats* relations,
                                   const ReferenceComparison* reference);

}  // namespace slamkit
