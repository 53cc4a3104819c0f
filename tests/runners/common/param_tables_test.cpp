// Every line of every config table (grid, feature log, exploration, iSAM, scenario): a file that
// sets only that key must load, with the real loader, to a JSON echo holding the value written
// at that key and every other key as without it. A line reading into another line's field, or
// echoing one, changes a second key; a line reading nothing leaves its own key as it was.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "common/temp_dir.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/features/exploration_config.hpp"
#include "slamkit/runners/features/feature_log_config.hpp"
#include "slamkit/runners/grid/grid_config.hpp"
#include "slamkit/runners/landmark/isam_config.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One config: its table (over defaults), the keys a file needs anyway, and its loader's echo.
struct Config {
  std::string name;
  std::function<config::ParamTable()> table;  // over an object the Config keeps
  json base;                                  // what every file holds besides the key under test
  // Keys a value of the key under test needs beside it (a world kind's clusters).
  std::function<json(const std::string& path, const json& value)> companions;
  std::function<json(const fs::path&)> load;
};

template <typename T>
std::function<config::ParamTable()> TableOf(config::ParamTable (*make)(T&)) {
  auto object = std::make_shared<T>();
  return [object, make] { return make(*object); };
}

json::json_pointer PointerOf(const config::Param& p) {
  std::string path = p.section;
  std::replace(path.begin(), path.end(), '.', '/');
  if (!path.empty()) path.insert(path.begin(), '/');
  path += '/';
  path += p.key;
  return json::json_pointer(path);
}

std::vector<double> NumberCandidates(const config::Param& p, const json& v) {
  if (v.is_null()) return {7.5};  // a limit that defaults to none
  const double x = v.get<double>();
  const double up = std::min(x + 0.25 + 0.5 * std::abs(x), p.max);
  std::vector<double> out;
  if (up != x) out.push_back(up);
  out.push_back(x > 0.0 ? x / 2.0 : x - 0.25 - 0.5 * std::abs(x));
  return out;
}

// Values different from `v` (the key's value without it) that its bound allows, best first: a
// later one is tried when the loader rejects an earlier one for another key's sake (a gate
// above the new-landmark gate).
std::vector<json> Candidates(const config::Param& p, const json& v) {
  struct Visitor {
    const config::Param& p;
    const json& v;
    std::vector<json> Numbers() const {
      std::vector<json> out;
      for (double x : NumberCandidates(p, v)) out.push_back(x);
      return out;
    }
    std::vector<json> Integers() const {
      const long x = v.get<long>();
      return {x + 1 <= p.max_int ? x + 1 : x - 1, x - 1};
    }
    std::vector<json> operator()(double*) const { return Numbers(); }
    std::vector<json> operator()(float*) const { return Numbers(); }
    std::vector<json> operator()(int*) const { return Integers(); }
    std::vector<json> operator()(long*) const { return Integers(); }
    std::vector<json> operator()(std::uint64_t*) const { return {v.get<std::uint64_t>() + 1}; }
    std::vector<json> operator()(bool*) const { return {!v.get<bool>()}; }
    std::vector<json> operator()(std::string*) const { return {v.get<std::string>() + "_x"}; }
    std::vector<json> operator()(Eigen::Vector2d*) const {
      const double x = v[0], y = v[1];
      return {json::array({x + 0.25 + 0.5 * std::abs(x), y + 0.5 + 0.5 * std::abs(y)}),
              json::array({x - 0.25 - 0.5 * std::abs(x), y - 0.5 - 0.5 * std::abs(y)})};
    }
    std::vector<json> operator()(std::optional<double>*) const {
      return v.is_null() ? std::vector<json>{20.0, 0.5} : Numbers();
    }
    std::vector<json> operator()(const config::ChoiceRef& c) const {
      std::vector<json> out;
      const auto at = std::find(c.names.begin(), c.names.end(), v.get<std::string>());
      const std::size_t i = static_cast<std::size_t>(at - c.names.begin());
      for (std::size_t k = 1; k < c.names.size(); ++k) {
        out.push_back(c.names[(i + k) % c.names.size()]);
      }
      return out;
    }
    std::vector<json> operator()(std::monostate) const { return {}; }
  };
  return std::visit(Visitor{p, v}, p.target);
}

::testing::AssertionResult SameValue(const json& got, const json& want) {
  if (got.is_number_integer() && want.is_number_integer()) {
    if (got == want) return ::testing::AssertionSuccess();
  } else if (got.is_number() && want.is_number()) {
    const double g = got.get<double>(), w = want.get<double>();
    // Degrees go through radians, floats through a float.
    if (std::abs(g - w) <= 1e-6 * std::max(1.0, std::abs(w))) return ::testing::AssertionSuccess();
  } else if (got.is_array() && want.is_array() && got.size() == want.size()) {
    for (std::size_t i = 0; i < got.size(); ++i) {
      if (!SameValue(got[i], want[i]))
        return ::testing::AssertionFailure() << got << " != " << want;
    }
    return ::testing::AssertionSuccess();
  } else if (got == want) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << got << " != " << want;
}

// The keys other than `at` (and its elements) whose values differ.
std::vector<std::string> OtherChanges(const json& got, const json& before,
                                      const json::json_pointer& at) {
  const json a = got.flatten(), b = before.flatten();
  const std::string own = at.to_string();
  std::set<std::string> keys;
  for (const auto& [k, v] : a.items()) keys.insert(k);
  for (const auto& [k, v] : b.items()) keys.insert(k);
  std::vector<std::string> changed;
  for (const std::string& k : keys) {
    if (k == own || k.rfind(own + "/", 0) == 0) continue;
    if (!a.contains(k) || !b.contains(k) || a[k] != b[k]) changed.push_back(k);
  }
  return changed;
}

class ParamTables : public testing::TempDirTest {
 protected:
  // Loads a file of `base` with `value` at `at` (and its companions); null when rejected.
  std::optional<json> LoadWith(const Config& c, const json::json_pointer& at, const json& value) {
    json file = c.base;
    file[at] = value;
    if (c.companions) file.merge_patch(c.companions(at.to_string(), value));
    try {
      return c.load(WriteFile(c.name + ".yaml", file.dump(2)));
    } catch (const InputError& e) {
      rejected_ = e.what();
      return std::nullopt;
    }
  }

  void WalkTable(const Config& c) {
    const json before = c.load(WriteFile(c.name + ".yaml", c.base.dump(2)));
    int checked = 0;
    for (const config::Param& p : c.table()) {
      const json::json_pointer at = PointerOf(p);
      const json old = before.contains(at) ? before[at] : json(nullptr);
      const std::vector<json> candidates = Candidates(p, old);
      if (std::holds_alternative<std::monostate>(p.target)) continue;  // read beside the table
      SCOPED_TRACE(c.name + ": " + p.Path());
      if (candidates.empty()) {
        // A choice of one (the grid's backend, for now) has nothing else to be.
        const auto* choice = std::get_if<config::ChoiceRef>(&p.target);
        EXPECT_TRUE(choice && choice->names.size() == 1) << "no value other than " << old;
        continue;
      }
      bool loaded = false;
      for (const json& value : candidates) {
        const std::optional<json> got = LoadWith(c, at, value);
        if (!got) continue;
        loaded = true;
        ASSERT_TRUE(got->contains(at)) << "the echo lacks the key";
        EXPECT_TRUE(SameValue((*got)[at], value)) << "written " << value;
        EXPECT_FALSE(SameValue((*got)[at], old)) << "unchanged";
        EXPECT_EQ(OtherChanges(*got, before, at), std::vector<std::string>{});
        break;
      }
      EXPECT_TRUE(loaded) << "every value rejected, the last: " << rejected_;
      ++checked;
    }
    EXPECT_GT(checked, 5);
  }

  std::string rejected_;
};

// Two lines reading into one field would make one key's file change two keys' echo (unless
// neither is written), so this says it directly: no two lines share a target.
TEST(ParamTableTargets, NoTwoLinesShareAField) {
  const std::vector<std::pair<std::string, std::function<config::ParamTable()>>> tables = {
      {"grid", TableOf(&GridParamTable)},
      {"feature log", TableOf(&FeatureLogParamTable)},
      {"exploration", TableOf(&ExplorationParamTable)},
      {"isam", TableOf(&IsamParamTable)},
      {"scenario", TableOf(&ScenarioParamTable)}};
  for (const auto& [name, table] : tables) {
    std::set<const void*> targets;
    std::set<std::string> paths;
    for (const config::Param& p : table()) {
      EXPECT_TRUE(paths.insert(p.Path()).second) << name << ": " << p.Path() << " twice";
      const void* address = std::visit(
          [](const auto& t) -> const void* {
            if constexpr (std::is_pointer_v<std::decay_t<decltype(t)>>) return t;
            return nullptr;
          },
          p.target);
      if (address) {
        EXPECT_TRUE(targets.insert(address).second) << name << ": " << p.Path();
      }
    }
  }
}

TEST_F(ParamTables, GridLinesRoundTrip) {
  WalkTable({"grid", TableOf(&GridParamTable), json::object(), nullptr,
             [](const fs::path& path) { return GridParamsJson(LoadGridConfig(path)); }});
}

TEST_F(ParamTables, FeatureLogLinesRoundTrip) {
  WalkTable(
      {"features", TableOf(&FeatureLogParamTable), json::object(), nullptr,
       [](const fs::path& path) { return FeatureLogParamsJson(LoadFeatureLogConfig(path)); }});
}

TEST_F(ParamTables, ExplorationLinesRoundTrip) {
  WalkTable(
      {"exploration",
       TableOf(&ExplorationParamTable),
       {{"world", "plan.txt"}},
       nullptr,
       [](const fs::path& path) { return ExplorationConfigJson(LoadExplorationConfig(path)); }});
}

TEST_F(ParamTables, IsamLinesRoundTrip) {
  // Both sighting sigmas set, so that either may change alone.
  const json base = {{"sightings", {{"sigma_range_m", 0.5}, {"sigma_bearing_deg", 2.0}}}};
  WalkTable({"isam", TableOf(&IsamParamTable), base, nullptr,
             [](const fs::path& path) { return IsamParamsJson(LoadIsamConfig(path)); }});
}

TEST_F(ParamTables, ScenarioLinesRoundTrip) {
  const json base = {{"route", {{"waypoints_m", {{0, 0}, {10, 0}}}}}};
  const auto companions = [](const std::string& path, const json& value) {
    if (path != "/world/kind") return json::object();
    if (value == "csv") return json{{"world", {{"landmarks_csv", "trees.csv"}}}};
    return json{{"world", {{"clusters", {{{"center_m", {1, 2}}, {"count", 3}}}}}}};
  };
  WriteFile("trees.csv", "id,x_m,y_m\n4,1,2\n");
  WalkTable({"scenario", TableOf(&ScenarioParamTable), base, companions, [](const fs::path& path) {
               ScenarioConfig loaded = LoadScenario(path);
               return config::ParamsJson(ScenarioParamTable(loaded));
             }});
}

}  // namespace
}  // namespace slamkit
