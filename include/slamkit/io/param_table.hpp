#pragma once

// One table per params struct: every parameter's place in a config file (section and key), its
// unit, the values it may take, what it means and its command-line flag. The YAML reader
// (ReadParams), the JSON echo of metrics.json (ParamsJson), the command line's options (apps)
// and the error messages all walk the same table, so that they cannot disagree and a new
// parameter is one line of it.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "slamkit/io/config_section.hpp"

namespace slamkit::config {

// A parameter that takes one of a list of names (an enum): its index in `names` is the value.
struct ChoiceRef {
  std::vector<std::string> names;
  std::function<int()> get;
  std::function<void(int)> set;
};

struct Param {
  std::string section;  // dotted path of its YAML map: "" for the top level, "motion", "a.b"
  std::string key;
  std::string unit;  // "m", "rad", "m/m", "s", ...; "" for counts, flags, factors and choices
  std::string help;
  std::string flag;  // its command-line option ("--particles"); "" when it has none
  // An optional number is left out of the JSON while unset; std::monostate is a key the table
  // lists (it is known to the reader and documented) but its caller reads: a list, a file name.
  std::variant<double*, float*, int*, long*, std::uint64_t*, bool*, std::string*, Eigen::Vector2d*,
               std::optional<double>*, ChoiceRef, std::monostate>
      target;
  Bound bound = Bound::kFinite;                          // a number's range
  double max = std::numeric_limits<double>::infinity();  // a number's inclusive upper limit
  int min = std::numeric_limits<int>::min();             // an integer's range
  int max_int = std::numeric_limits<int>::max();
  bool null_is_infinity = false;  // a number that may be "none": null in YAML and in JSON
  bool degrees = false;           // a double* in radians whose YAML and JSON value is in degrees

  std::string Path() const { return section.empty() ? key : section + "." + key; }
};

using ParamTable = std::vector<Param>;

// The table's lines, built with the target's type deduced.
Param Number(std::string section, std::string key, double* v, Bound bound, std::string unit,
             std::string help);
Param Number(std::string section, std::string key, float* v, Bound bound, std::string unit,
             std::string help);
// A number whose "none" (infinity) is null in YAML and JSON: a limit that may be absent.
Param Limit(std::string section, std::string key, double* v, std::string unit, std::string help,
            Bound bound = Bound::kNonNegative);
// An angle kept in radians that the file and the JSON give in degrees (its unit: "deg",
// "deg/s"); `max` (AtMost) is in degrees too.
Param Degrees(std::string section, std::string key, double* rad, Bound bound, std::string unit,
              std::string help);
// A number that may be unset: absent from the JSON then.
Param Optional(std::string section, std::string key, std::optional<double>* v, Bound bound,
               std::string unit, std::string help);
Param Integer(std::string section, std::string key, int* v, int min, std::string help);
// Read as an int (so within int's range), kept in a long.
Param Integer(std::string section, std::string key, long* v, int min, std::string help);
Param Text(std::string section, std::string key, std::string* v, std::string help);
// An [x, y] pair in metres.
Param Point(std::string section, std::string key, Eigen::Vector2d* v, std::string help);
// A key its caller reads beside the table (a list, a file name, a pose): known to the reader.
Param Listed(std::string section, std::string key, std::string help);
Param Seed(std::string section, std::string key, std::uint64_t* v, std::string help);
Param Flag(std::string section, std::string key, bool* v, std::string help);
template <typename Enum>
Param Choice(std::string section, std::string key, Enum* v, std::vector<std::string> names,
             std::string help) {
  Param p{std::move(section), std::move(key), "", std::move(help), "", ChoiceRef{}};
  p.target = ChoiceRef{std::move(names), [v] { return static_cast<int>(*v); },
                       [v](int i) { *v = static_cast<Enum>(i); }};
  return p;
}
// `param` with a command-line flag and, optionally, an upper limit (both return it).
Param WithFlag(Param param, std::string flag);
Param AtMost(Param param, double max);

// The sections the table names below `section` ("" for the root), in first-mention order.
std::vector<std::string> ChildSections(const ParamTable& table, const std::string& section);
// The keys Section must accept in `section`: its params' keys and its child sections.
std::vector<std::string> KnownKeys(const ParamTable& table, const std::string& section);

// The map of the config at dotted `section` of `root`, checked against the table's keys there:
// for the caller's own checks and messages after ReadParams.
Section TableSection(const YAML::Node& root, const std::string& file, const ParamTable& table,
                     const std::string& section, const std::vector<std::string>& extra_keys = {});

// Reads every parameter of `table` from `root` (a config file's document, `file` its name for
// errors), keeping the target's value where a key is absent. Unknown keys, wrong types and
// values out of range are InputErrors naming the file, the line and the key path. `extra_keys`
// are accepted at the top level and left to the caller (sections of another table, a file
// name).
void ReadParams(const YAML::Node& root, const std::string& file, const ParamTable& table,
                const std::vector<std::string>& extra_keys = {});
// The table's values as nested JSON objects, one per section, with the file's keys (not the
// Listed ones): written back as YAML, it reads to the same values.
nlohmann::json ParamsJson(const ParamTable& table);

}  // namespace slamkit::config
