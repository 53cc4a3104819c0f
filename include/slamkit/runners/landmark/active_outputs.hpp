#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/runners/landmark/active_monte_carlo.hpp"
#include "slamkit/runners/landmark/filter_choice.hpp"

namespace slamkit {

// One route section of one run (metrics.json's per_run[k].sections[i]): `first_period`,
// `end_period` (-1: open at the end of the run), `route_waypoint`, `detour_m` ([x, y] or null),
// `detour_reached`, `periods`, `observations`, `landmarks`, `observations_per_period`,
// `observations_per_landmark`.
nlohmann::json SectionStatsJson(const SectionStats& s);

// Seed 001's Tables 1-3 (metrics.json's `sections`): per section, `section` (from 1), `runs`
// (runs that have it) and the means over them of `periods`, `observations`, `landmarks`,
// `observations_per_period`, `observations_per_landmark`.
nlohmann::json SectionMeansJson(const std::vector<SectionMean>& sections);

// The summary lines of SectionMeansJson for a terminal, one per section ("  section 1 (50
// runs): 415.7 observations, 13.5 per period, 20.2 per landmark\n").
std::string SectionMeansText(const std::vector<SectionMean>& sections);

// What a closed-loop run adds to its per_run entry: `steps`, `periods`, `sections` and
// `detours` (the chosen cluster centres, [[x, y], ...]).
nlohmann::json ActiveRunTraceJson(const ActiveRunTrace& trace);

// metrics.json of `slamkit mc`: MonteCarloMetrics' keys, `filter`, `particles` (FastSLAM only),
// `planner` (`route` or `swslam`) and `sections`.
nlohmann::json ActiveMonteCarloMetrics(const ScenarioConfig& config, const MonteCarloParams& params,
                                       const ActiveMonteCarloResult& result, FilterKind filter,
                                       int particles);

}  // namespace slamkit
