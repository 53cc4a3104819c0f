#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slamkit/eval/trajectory_errors.hpp"

namespace slamkit {

// One log of a grid-SLAM suite and what to score it against.
struct SuiteLog {
  std::string name;                   // unique within the suite; names its output folder
  std::filesystem::path log;          // CARMEN log (plain or gzip)
  std::filesystem::path relations;    // relations file (Kümmerle et al. 2009); empty: none
  std::filesystem::path reference;    // per-scan reference poses; empty: none
  bool reference_from_log = false;    // the log's own poses are the reference (corrected logs)
  PairBy pair_by = PairBy::kTime;     // how `reference` poses pair with scans
};

struct SuiteManifest {
  std::filesystem::path file;  // where it was read from
  std::vector<SuiteLog> logs;
};

// Reads a suite manifest (docs/suite.md; configs/carmen_suite.yaml):
//   root: ../../shared/datasets/carmen      # optional; relative to the manifest's folder
//   logs:
//     - {name: intel, log: intel.clf, relations: intel.relations}
//     - {name: csail, log: suite/csail.log.gz, reference: suite/csail.reference.txt,
//        pair_by: index}
// Paths are relative to `root` (`root_override`, when not empty, replaces it). Throws InputError
// naming the file, line and key for an unknown key, a missing file, an unknown pairing, a
// repeated name, both `reference` and `reference_from_log`, or an empty list.
SuiteManifest LoadSuiteManifest(const std::filesystem::path& path,
                                const std::filesystem::path& root_override = {});

}  // namespace slamkit
