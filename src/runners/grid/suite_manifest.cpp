#include "slamkit/runners/grid/suite_manifest.hpp"

#include <set>
#include <string>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "slamkit/io/config_section.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

using config::Section;

// `key`'s path under `root`, which must name an existing file (when the key is present).
std::filesystem::path ExistingFile(const Section& s, const std::string& key,
                                   const std::filesystem::path& root) {
  std::string relative;
  s.Read(key, &relative);
  if (!s.Has(key)) return {};
  if (relative.empty()) s.Fail(key, "must not be empty");
  const std::filesystem::path path = root / relative;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    s.Fail(key, fmt::format("no such file: {}", path.string()));
  }
  return path;
}

SuiteLog ReadLog(const Section& s, const std::filesystem::path& root) {
  SuiteLog log;
  s.Read("name", &log.name);
  const bool bad_name = log.name.empty() || log.name[0] == '.' ||
                        log.name.find_first_of("/\\") != std::string::npos;
  if (bad_name) {
    s.Fail("name", "required: a non-empty name without '/', not starting with '.'");
  }
  log.log = ExistingFile(s, "log", root);
  if (log.log.empty()) s.Fail("log", "required (the CARMEN log)");
  log.relations = ExistingFile(s, "relations", root);
  log.reference = ExistingFile(s, "reference", root);
  s.Read("reference_from_log", &log.reference_from_log);
  if (log.reference_from_log && !log.reference.empty()) {
    s.Fail("reference_from_log", "give either `reference` or `reference_from_log`, not both");
  }
  log.pair_by = static_cast<PairBy>(config::ReadChoice(s, "pair_by", {"time", "index"}, 0));
  if (s.Has("pair_by") && log.reference.empty()) {
    s.Fail("pair_by", "pairs `reference` poses, and there is no `reference`");
  }
  return log;
}

}  // namespace

SuiteManifest LoadSuiteManifest(const std::filesystem::path& path,
                                const std::filesystem::path& root_override) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  const Section top(yaml, path.string(), "", {"root", "logs"});
  std::string root_text;
  top.Read("root", &root_text);
  std::filesystem::path root = path.parent_path() / root_text;
  if (!root_override.empty()) root = root_override;
  const YAML::Node logs = top.Get("logs");
  if (!logs || !logs.IsSequence() || logs.size() == 0) {
    top.Fail("logs", "required: a list of logs ({name, log, ...} maps)");
  }
  SuiteManifest manifest{path, {}};
  std::set<std::string> names;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const Section s(logs[i], path.string(), fmt::format("logs[{}]", i),
                    {"name", "log", "relations", "reference", "reference_from_log", "pair_by"});
    SuiteLog log = ReadLog(s, root);
    if (!names.insert(log.name).second) {
      s.Fail("name", fmt::format("'{}' names another log already", log.name));
    }
    manifest.logs.push_back(std::move(log));
  }
  return manifest;
}

}  // namespace slamkit
