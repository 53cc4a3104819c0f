#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "slamkit/io/param_table.hpp"
#include "slamkit/runners/features/feature_log_run.hpp"

namespace slamkit {

// The feature log's parameter table (io/param_table.hpp), its lines pointing into `params`:
// what LoadFeatureLogConfig reads and FeatureLogParamsJson writes.
config::ParamTable FeatureLogParamTable(FeatureLogParams& params);

// Reads the line-and-corner EKF's parameters for a log from a YAML file (configs/features.yaml
// lists every key with its unit and default; keys left out keep `defaults`). Throws InputError
// naming the file, line and key for an unknown key, a wrong type, a value out of range or an
// unknown policy.
FeatureLogParams LoadFeatureLogConfig(const std::filesystem::path& path,
                                      const FeatureLogParams& defaults = {});

// Every parameter LoadFeatureLogConfig reads, with the same keys (infinity as null): a run's
// effective parameters, which load back to the same values when written as YAML.
nlohmann::json FeatureLogParamsJson(const FeatureLogParams& params);

}  // namespace slamkit
