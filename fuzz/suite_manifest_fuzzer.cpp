// LoadSuiteManifest (a YAML list of logs with their references). The manifest's folder holds a
// log and a reference file, so that inputs naming them get past the existence checks.

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/grid/suite_manifest.hpp"

int slamkit::fuzz::FuzzSuiteManifest(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  static const bool files = [] {
    WriteFile("a.log", "FLASER 3 1 2 3 0 0 0 0 0 0 1 host 1\n");
    WriteFile("a.ref", "1 0 0 0\n");
    return true;
  }();
  (void)files;
  try {
    const slamkit::SuiteManifest m =
        slamkit::LoadSuiteManifest(WriteFile("suite.yaml", AsText(data, size)));
    Check(!m.logs.empty(), "a manifest lists at least one log");
    std::set<std::string> names;
    for (const auto& log : m.logs) {
      Check(!log.name.empty() && names.insert(log.name).second, "names are unique, not empty");
      Check(!log.log.empty(), "every log has its file");
      Check(!(log.reference_from_log && !log.reference.empty()), "one reference at most");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
