#pragma once

// Typed, validated reading of YAML config maps. Every error is an InputError that names the file,
// the line and the full key path, so a user can find the mistake without reading the code. Used
// by io's readers and by the modules that map a config onto their params (runners); only io
// opens the files.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace slamkit::config {

// The YAML document in `path`; InputError naming the file for an unreadable file or a syntax
// error (with its line).
YAML::Node LoadYamlFile(const std::filesystem::path& path);

// The range a number must lie in, beyond being finite.
enum class Bound { kFinite, kNonNegative, kPositive };

// `node` as quoted in an error message: its scalar text, or its kind.
std::string Describe(const YAML::Node& node);

// One YAML map of the config: checks its keys against the known ones and reads typed values,
// leaving the output untouched when a key is absent. Errors name the file, line and key path.
class Section {
 public:
  // `path` is the dotted key path of `node` ("" for the file's root); a null node is an absent,
  // empty section. Throws InputError for a non-map, an unknown key or a duplicate key.
  Section(const YAML::Node& node, std::string file, std::string path,
          std::vector<std::string> known);

  bool Has(const std::string& key) const { return line_of_key_.count(key) > 0; }
  YAML::Node Get(const std::string& key) const { return node_[key]; }
  Section Child(const std::string& key, std::vector<std::string> known) const;
  std::string Path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }

  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const;
  [[noreturn]] void FailAt(const YAML::Node& at, const std::string& message) const;

  // `value` (found under `key`) as a finite number within `bound`.
  double Number(const std::string& key, const YAML::Node& value, Bound bound) const;
  void Read(const std::string& key, double* out, Bound bound = Bound::kFinite) const;
  // A value given in degrees, stored in radians (finite too: an error for one too large).
  void ReadDegrees(const std::string& key, double* out_rad, Bound bound) const;
  void Read(const std::string& key, int* out, int min) const;
  void Read(const std::string& key, std::uint64_t* out) const;
  void Read(const std::string& key, bool* out) const;
  void Read(const std::string& key, std::string* out) const;
  // An [x, y] pair in metres.
  Eigen::Vector2d Point(const std::string& key, const YAML::Node& value) const;
  void Read(const std::string& key, Eigen::Vector2d* out) const;

 private:
  void CheckKeys(const std::vector<std::string>& known);

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::map<std::string, int> line_of_key_;
};

// Reads `key` as one of `names` (whose index is the returned value), or `fallback` when absent.
int ReadChoice(const Section& s, const std::string& key, const std::vector<std::string>& names,
               int fallback);

}  // namespace slamkit::config
