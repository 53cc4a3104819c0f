#include "slamkit/io/param_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

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

void ReadNumber(const Section& s, const Param& p, double* v) {
  if (p.null_is_infinity && s.Has(p.key) && s.Get(p.key).IsNull()) {
    *v = std::numeric_limits<double>::infinity();
    return;
  }
  s.Read(p.key, v, p.bound);
  if (s.Has(p.key) && *v > p.max) s.Fail(p.key, "must be at most " + Text(p.max));
}

void ReadParam(const Section& s, const Param& p) {
  std::visit(Overloaded{
                 [&](double* v) { ReadNumber(s, p, v); },
                 [&](float* v) {
                   double value = *v;
                   ReadNumber(s, p, &value);
                   *v = static_cast<float>(value);
                 },
                 [&](int* v) {
                   s.Read(p.key, v, p.min);
                   if (s.Has(p.key) && *v > p.max_int) {
                     s.Fail(p.key, "must be at most " + std::to_string(p.max_int));
                   }
                 },
                 [&](std::uint64_t* v) { s.Read(p.key, v); },
                 [&](bool* v) { s.Read(p.key, v); },
                 [&](const ChoiceRef& c) { c.set(ReadChoice(s, p.key, c.names, c.get())); },
             },
             p.target);
}

nlohmann::json ParamJson(const Param& p) {
  return std::visit(Overloaded{
                        [&](double* v) {
                          if (p.null_is_infinity && !std::isfinite(*v)) {
                            return nlohmann::json(nullptr);
                          }
                          return nlohmann::json(*v);
                        },
                        [](float* v) { return nlohmann::json(*v); },
                        [](int* v) { return nlohmann::json(*v); },
                        [](std::uint64_t* v) { return nlohmann::json(*v); },
                        [](bool* v) { return nlohmann::json(*v); },
                        [](const ChoiceRef& c) { return nlohmann::json(c.names.at(c.get())); },
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

Param Limit(std::string section, std::string key, double* v, std::string unit, std::string help) {
  Param p = Number(std::move(section), std::move(key), v, Bound::kNonNegative, std::move(unit),
                   std::move(help));
  p.null_is_infinity = true;
  return p;
}

Param Integer(std::string section, std::string key, int* v, int min, std::string help) {
  Param p{std::move(section), std::move(key), "", std::move(help), "", v};
  p.min = min;
  return p;
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

void ReadParams(const YAML::Node& root, const std::string& file, const ParamTable& table,
                const std::vector<std::string>& extra_keys) {
  std::vector<std::string> known = KnownKeys(table, "");
  known.insert(known.end(), extra_keys.begin(), extra_keys.end());
  ReadSection(Section(root, file, "", known), "", table);
}

nlohmann::json ParamsJson(const ParamTable& table) {
  nlohmann::json j = nlohmann::json::object();
  for (const Param& p : table) {
    nlohmann::json* at = &j;
    std::stringstream parts(p.section);
    for (std::string part; std::getline(parts, part, '.');) at = &(*at)[part];
    (*at)[p.key] = ParamJson(p);
  }
  return j;
}

}  // namespace slamkit::config
