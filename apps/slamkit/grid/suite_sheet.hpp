#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slamkit/runners/grid/suite_summary.hpp"

namespace slamkit::app {

// Where a suite output keeps run `r`: DIR/runs/LOG/seed_S, or DIR/runs/LOG/graph.
std::filesystem::path SuiteRunDir(const std::filesystem::path& dir, const SuiteRunRecord& r);

// DIR/maps.png: every run's map with its path (and, dimmer, the raw odometry), so that a broken
// map is seen at a glance.
void WriteSuiteContactSheet(const std::filesystem::path& dir,
                            const std::vector<SuiteRunRecord>& records, const std::string& title);

}  // namespace slamkit::app
