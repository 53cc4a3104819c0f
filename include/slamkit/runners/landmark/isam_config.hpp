#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "slamkit/io/param_table.hpp"
#include "slamkit/runners/landmark/isam_run.hpp"

namespace slamkit {

// The iSAM runner's parameter table (io/param_table.hpp), its lines pointing into `params`:
// what LoadIsamConfig reads (then checking the keys against each other) and IsamParamsJson
// writes. FastSLAM's unset gates are left out of the JSON (they follow the EKF's).
config::ParamTable IsamParamTable(IsamRunParams& params);

// Reads the iSAM runner's parameters from a YAML file (configs/victoria_park.yaml lists every key
// with its unit; keys left out keep `defaults`). Throws InputError naming the file, line and key
// for an unknown key, a wrong type, a value out of range or an unknown choice.
IsamRunParams LoadIsamConfig(const std::filesystem::path& path, const IsamRunParams& defaults = {});

// Every parameter LoadIsamConfig reads, with the same keys (metrics.json's `params`).
nlohmann::json IsamParamsJson(const IsamRunParams& params);

}  // namespace slamkit
