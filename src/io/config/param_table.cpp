#include "slamkit/io/param_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "slamkit/core/angle.hpp"

namespace slamkit::config {
namespace {

template <typename... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <typename... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

std::string Text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void CheckAtMost(const Section& s, const Param& p, double value) {
  if (value > p.max) s.Fail(p.key, "must be at most " + Text(p.max));
}

void ReadNumber(const Section& s, const Param& p, double* v) {
  if (!s.Has(p.key)) return;
  if (p.null_is_infinity && s.Get(p.key).IsNull()) {
    *v = std::numeric_limits<double>::infinity();
    return;
  }
  if (!p.degrees) {
    s.Read(p.key, v, p.bound);
    CheckAtMost(s, p, *v);
    return;
  }
  s.ReadDegrees(p.key, v, p.bound);
  CheckAtMost(s, p, s.Number(p.key, s.Get(p.key), p.bound));
}

void ReadInteger(const Section& s, const Param& p, int* v) {
  s.Read(p.key, v, p.min);
  if (s.Has(p.key) && *v > p.max_int) {
    s.Fail(p.key, "must be at most " + std::to_string(p.max_int));
  }
}

void ReadParam(const Section& s, const Param& p) {
  std::visit(Overloaded{
                 [&](double* v) { ReadNumber(s, p, v); },
                 [&](float* v) {
                   double value = *v;
                   ReadNumber(s, p, &value);
                   *v = static_cast<float>(value);
                 },
                 [&](int* v) { ReadInteger(s, p, v); },
                 [&](long* v) {
                   int value = 0;
                   ReadInteger(s, p, &value);
                   if (s.Has(p.key)) *v = value;
                 },
                 [&](std::uint64_t* v) { s.Read(p.key, v); },
                 [&](bool* v) { s.Read(p.key, v); },
                 [&](std::string* v) { s.Read(p.key, v); },
                 [&](Eigen::Vector2d* v) { s.Read(p.key, v); },
                 [&](std::optional<double>* v) {
                   double value = 0.0;
                   ReadNumber(s, p, &value);
                   if (s.Has(p.key)) *v = value;
                 },
                 [&](const ChoiceRef& c) { c.set(ReadChoice(s, p.key, c.names, c.get())); },
                 [](std::monostate) {},
             },
             p.target);
}

// Its JSON value; null for a line the JSON leaves out (Listed, an unset Optional).
std::optional<nlohmann::json> ParamJson(const Param& p) {
  using Json = std::optional<nlohmann::json>;
  return std::visit(Overloaded{
                        [&](double* v) {
                          if (p.null_is_infinity && !std::isfinite(*v)) return Json(nullptr);
                          return Json(p.degrees ? RadToDeg(*v) : *v);
                        },
                        [](float* v) { return Json(*v); },
                        [](int* v) { return Json(*v); },
                        [](long* v) { return Json(*v); },
                        [](std::uint64_t* v) { return Json(*v); },
                        [](bool* v) { return Json(*v); },
                        [](std::string* v) { return Json(*v); },
                        [](Eigen::Vector2d* v) {
                          return Json(nlohmann::json::array({v->x(), v->y()}));
                        },
                        [](std::optional<double>* v) { return *v ? Json(**v) : std::nullopt; },
                        [](const ChoiceRef& c) { return Json(c.names.at(c.get())); },
                        [](std::monostate) { return Json(); },
                    },
                    p.target);
}

// The last part of a dotted section path ("a.b" -> "b").
std::string LastPart(const std::string& section) {
  const std::size_t dot = section.rfind('.');
  return dot == std::string::npos ? section : section.substr(dot + 1);
}

void ReadSection(const Section& s, const std::string& section, const ParamTable& table) {
  for (const Param& p : table) {
    if (p.section == section) ReadParam(s, p);
  }
  for (const std::string& child : ChildSections(table, section)) {
    ReadSection(s.Child(LastPart(child), KnownKeys(table, child)), child, table);
  }
}

// The section at dotted `rest` below `s` (at `path`). Recursive rather than a loop assigning
// Sections: assigning a YAML::Node rewrites the node it refers to.
Section Descend(const Section& s, const ParamTable& table, const std::string& path,
                const std::string& rest) {
  if (rest.empty()) return s;
  const std::size_t dot = rest.find('.');
  const std::string part = rest.substr(0, dot);
  const std::string child = path.empty() ? part : path + "." + part;
  return Descend(s.Child(part, KnownKeys(table, child)), table, child,
                 dot == std::string::npos ? "" : rest.substr(dot + 1));
}

}  // namespace

Param Number(std::string section, std::string key, double* v, Bound bound, std::string unit,
             std::string help) {
  Param p{std::move(section), std::move(key), std::move(unit), std::move(help), "", v};
  p.bound = bound;
  return p;
}

Param Number(std::string section, std::string key, float* v, Bound bound, std::string unit,
             std::string help) {
  Param p{std::move(section), std::move(key), std::move(unit), std::move(help), "", v};
  p.bound = bound;
  return p;
}

Param Limit(std::string section, std::string key, double* v, std::string unit, std::string help,
            Bound bound) {
  Param p = Number(std::move(section), std::move(key), v, bound, std::move(unit), std::move(help));
  p.null_is_infinity = true;
  return p;
}

Param Degrees(std::string section, std::string key, double* rad, Bound bound, std::string unit,
              std::string help) {
  Param p =
      Number(std::move(section), std::move(key), rad, bound, std::move(unit), std::move(help));
  p.degrees = true;
  return p;
}

Param Optional(std::string section, std::string key, std::optional<double>* v, Bound bound,
               std::string unit, std::string help) {
  Param p{std::move(section), std::move(key), std::move(unit), std::move(help), "", v};
  p.bound = bound;
  return p;
}

Param Integer(std::string section, std::string key, int* v, int min, std::string help) {
  Param p{std::move(section), std::move(key), "", std::move(help), "", v};
  p.min = min;
  return p;
}

Param Integer(std::string section, std::string key, long* v, int min, std::string help) {
  Param p{std::move(section), std::move(key), "", std::move(help), "", v};
  p.min = min;
  return p;
}

Param Text(std::string section, std::string key, std::string* v, std::string help) {
  return {std::move(section), std::move(key), "", std::move(help), "", v};
}

Param Point(std::string section, std::string key, Eigen::Vector2d* v, std::string help) {
  return {std::move(section), std::move(key), "m", std::move(help), "", v};
}

Param Listed(std::string section, std::string key, std::string help) {
  return {std::move(section), std::move(key), "", std::move(help), "", std::monostate{}};
}

Param Seed(std::string section, std::string key, std::uint64_t* v, std::string help) {
  return {std::move(section), std::move(key), "", std::move(help), "", v};
}

Param Flag(std::string section, std::string key, bool* v, std::string help) {
  return {std::move(section), std::move(key), "", std::move(help), "", v};
}

Param WithFlag(Param param, std::string flag) {
  param.flag = std::move(flag);
  return param;
}

Param AtMost(Param param, double max) {
  param.max = max;
  param.max_int = static_cast<int>(std::min<double>(max, std::numeric_limits<int>::max()));
  return param;
}

std::vector<std::string> ChildSections(const ParamTable& table, const std::string& section) {
  std::vector<std::string> children;
  const std::string prefix = section.empty() ? "" : section + ".";
  for (const Param& p : table) {
    if (p.section.size() <= prefix.size() || p.section.compare(0, prefix.size(), prefix) != 0) {
      continue;
    }
    const std::size_t dot = p.section.find('.', prefix.size());
    const std::string child = p.section.substr(0, dot);
    if (std::find(children.begin(), children.end(), child) == children.end()) {
      children.push_back(child);
    }
  }
  return children;
}

std::vector<std::string> KnownKeys(const ParamTable& table, const std::string& section) {
  std::vector<std::string> keys;
  for (const Param& p : table) {
    if (p.section == section) keys.push_back(p.key);
  }
  for (const std::string& child : ChildSections(table, section)) keys.push_back(LastPart(child));
  return keys;
}

Section TableSection(const YAML::Node& root, const std::string& file, const ParamTable& table,
                     const std::string& section, const std::vector<std::string>& extra_keys) {
  std::vector<std::string> known = KnownKeys(table, "");
  known.insert(known.end(), extra_keys.begin(), extra_keys.end());
  return Descend(Section(root, file, "", known), table, "", section);
}

void ReadParams(const YAML::Node& root, const std::string& file, const ParamTable& table,
                const std::vector<std::string>& extra_keys) {
  std::vector<std::string> known = KnownKeys(table, "");
  known.insert(known.end(), extra_keys.begin(), extra_keys.end());
  ReadSection(Section(root, file, "", known), "", table);
}

nlohmann::json ParamsJson(const ParamTable& table) {
  nlohmann::json j = nlohmann::json::object();
  for (const Param& p : table) {
    std::optional<nlohmann::json> value = ParamJson(p);
    if (!value) continue;
    nlohmann::json* at = &j;
    std::stringstream parts(p.section);
    for (std::string part; std::getline(parts, part, '.');) at = &(*at)[part];
    (*at)[p.key] = std::move(*value);
  }
  return j;
}

}  // namespace slamkit::config
