#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace slamkit {

// A JSON file (a run's metrics.json, a suite's summary.json); InputError naming the file when it
// cannot be opened or is not JSON (with the parser's position).
nlohmann::json ReadJson(const std::filesystem::path& path);

}  // namespace slamkit
