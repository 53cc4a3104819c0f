#pragma once

#include <filesystem>
#include <string>

#include "slamkit/runners/landmark/active_monte_carlo.hpp"

namespace slamkit::app {

// map.png (run `first_run`, the first the study ran: its path, map and detours) and
// consistency.png (ANEES with its band, RMSE per step) of a Monte Carlo study.
void WriteMonteCarloFigures(const std::filesystem::path& dir, const std::string& scenario,
                            const ActiveMonteCarloResult& result, int first_run);
// consistency.png alone.
void WriteConsistencyPng(const std::filesystem::path& dir, const std::string& scenario,
                         const MonteCarloResult& mc);

}  // namespace slamkit::app
