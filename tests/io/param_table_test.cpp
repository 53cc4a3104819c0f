#include "slamkit/io/param_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit::config {
namespace {

enum class Colour { kRed, kGreen, kBlue };

// A params struct of every line kind, two sections deep.
struct Params {
  double gain = 1.0;
  double limit_m = std::numeric_limits<double>::infinity();
  double fraction = 0.5;
  double angle_rad = DegToRad(10.0);
  float weight = 0.25f;
  int count = 3;
  long tests = 100;
  std::uint64_t seed = 7;
  bool on = false;
  std::string name = "p";
  Eigen::Vector2d corner_m{1.0, 2.0};
  std::optional<double> gate;
  Colour colour = Colour::kGreen;
};

ParamTable TableOf(Params& p) {
  return {
      Number("", "gain", &p.gain, Bound::kPositive, "", "a gain"),
      Limit("outer", "limit_m", &p.limit_m, "m", "a limit (null: none)"),
      AtMost(Number("outer", "fraction", &p.fraction, Bound::kNonNegative, "", "a fraction"), 1.0),
      Degrees("outer.inner", "angle_deg", &p.angle_rad, Bound::kFinite, "deg", "an angle"),
      Number("outer.inner", "weight", &p.weight, Bound::kFinite, "", "a float"),
      AtMost(Integer("outer.inner", "count", &p.count, 1, "a count"), 5),
      Integer("", "tests", &p.tests, 1, "a long"),
      Seed("", "seed", &p.seed, "a seed"),
      Flag("", "on", &p.on, "a flag"),
      Text("", "name", &p.name, "a name"),
      Point("outer", "corner_m", &p.corner_m, "a point"),
      Optional("outer", "gate", &p.gate, Bound::kPositive, "", "a gate (unset: none)"),
      Choice("", "colour", &p.colour, {"red", "green", "blue"}, "a choice"),
      Listed("outer", "items", "a list its caller reads"),
  };
}

class ParamTableRead : public testing::TempDirTest {
 protected:
  Params Load(const std::string& text) {
    Params p;
    const std::filesystem::path path = WriteFile("t.yaml", text);
    ReadParams(LoadYamlFile(path), "t.yaml", TableOf(p), {"extra"});
    return p;
  }
  std::string ErrorOf(const std::string& text) {
    return testing::InputErrorOf([&] { Load(text); });
  }
};

TEST_F(ParamTableRead, ReadsEveryKindInNestedSections) {
  const Params p = Load(
      "gain: 2\ntests: 5\nseed: 9\non: true\nname: q\ncolour: blue\nextra: [1]\n"
      "outer:\n  limit_m: 4\n  fraction: 1\n  corner_m: [3, 4]\n  gate: 6\n  items: [x]\n"
      "  inner: {angle_deg: 90, weight: 0.5, count: 5}\n");
  EXPECT_EQ(p.gain, 2.0);
  EXPECT_EQ(p.limit_m, 4.0);
  EXPECT_EQ(p.fraction, 1.0);
  EXPECT_DOUBLE_EQ(p.angle_rad, M_PI / 2);
  EXPECT_EQ(p.weight, 0.5f);
  EXPECT_EQ(p.count, 5);
  EXPECT_EQ(p.tests, 5);
  EXPECT_EQ(p.seed, 9u);
  EXPECT_TRUE(p.on);
  EXPECT_EQ(p.name, "q");
  EXPECT_EQ(p.corner_m, Eigen::Vector2d(3, 4));
  EXPECT_EQ(p.gate, 6.0);
  EXPECT_EQ(p.colour, Colour::kBlue);
}

TEST_F(ParamTableRead, AbsentKeysKeepTheirValues) {
  const Params p = Load("outer: {inner: {}}\n");
  const Params defaults;
  EXPECT_EQ(p.gain, defaults.gain);
  EXPECT_TRUE(std::isinf(p.limit_m));
  EXPECT_EQ(p.angle_rad, defaults.angle_rad);
  EXPECT_FALSE(p.gate);
  EXPECT_EQ(p.colour, Colour::kGreen);
}

TEST_F(ParamTableRead, NullIsNoLimit) {
  Params p;
  p.limit_m = 3.0;
  ReadParams(LoadYamlFile(WriteFile("t.yaml", "outer: {limit_m: null}\n")), "t.yaml", TableOf(p));
  EXPECT_TRUE(std::isinf(p.limit_m));
  EXPECT_TRUE(
      testing::Contains(ErrorOf("gain: null\n"), "t.yaml:1: key 'gain': expected a number"));
}

TEST_F(ParamTableRead, MistakesNameFileLineAndKeyPath) {
  const std::pair<std::string, std::string> cases[] = {
      {"gian: 1\n", "t.yaml:1: unknown key 'gian' in section 'root'"},
      {"outer:\n  inner:\n    cuont: 1\n",
       "t.yaml:3: unknown key 'cuont' in section 'outer.inner'"},
      {"items: 1\n", "unknown key 'items'"},  // Listed in `outer` only
      {"gain: 0\n", "t.yaml:1: key 'gain': must be > 0"},
      {"outer: {fraction: 1.5}\n", "t.yaml:1: key 'outer.fraction': must be at most 1"},
      {"outer:\n  inner: {count: 6}\n", "t.yaml:2: key 'outer.inner.count': must be at most 5"},
      {"outer:\n  inner: {count: 0}\n", "t.yaml:2: key 'outer.inner.count': must be >= 1"},
      {"outer: {limit_m: -1}\n", "key 'outer.limit_m': must be >= 0"},
      {"outer: {gate: 0}\n", "key 'outer.gate': must be > 0"},
      {"outer: {corner_m: [1]}\n", "key 'outer.corner_m': expected a point [x, y]"},
      {"outer: {inner: {angle_deg: 1e308}}\n", "key 'outer.inner.angle_deg': too large"},
      {"colour: pink\n", "t.yaml:1: key 'colour': expected one of red, green, blue"},
      {"on: maybe\n", "key 'on': expected true or false"},
      {"tests: 2.5\n", "key 'tests': expected an integer"},
      {"outer: 3\n", "t.yaml:1: key 'outer': expected a map"},
  };
  for (const auto& [text, part] : cases) {
    EXPECT_TRUE(testing::Contains(ErrorOf(text), part)) << text;
  }
}

// The section a caller's own checks fail in: the file's line and the key's full path.
TEST_F(ParamTableRead, TableSectionNamesTheLineOfANestedKey) {
  Params p;
  const ParamTable t = TableOf(p);
  const YAML::Node yaml =
      LoadYamlFile(WriteFile("t.yaml", "extra: 1\nouter:\n  inner:\n    count: 2\n"));
  const Section inner = TableSection(yaml, "t.yaml", t, "outer.inner", {"extra"});
  EXPECT_TRUE(inner.Has("count"));
  EXPECT_TRUE(testing::Contains(testing::InputErrorOf([&] { inner.Fail("count", "too many"); }),
                                "t.yaml:4: key 'outer.inner.count': too many"));
  EXPECT_THROW(TableSection(yaml, "t.yaml", t, ""), InputError);  // `extra` unknown without it
  // Reading the document again finds it as it was.
  EXPECT_TRUE(TableSection(yaml, "t.yaml", t, "outer", {"extra"}).Has("inner"));
}

TEST(ParamTableJson, EchoesNestedSectionsInTheFilesUnits) {
  Params p;
  p.gate = 4.0;
  const nlohmann::json j = ParamsJson(TableOf(p));
  EXPECT_EQ(j["gain"], 1.0);
  EXPECT_TRUE(j["outer"]["limit_m"].is_null());
  EXPECT_DOUBLE_EQ(j["outer"]["inner"]["angle_deg"].get<double>(), 10.0);
  EXPECT_EQ(j["outer"]["inner"]["count"], 3);
  EXPECT_TRUE(j["outer"]["inner"]["count"].is_number_integer());
  EXPECT_EQ(j["tests"], 100);
  EXPECT_TRUE(j["seed"].is_number_unsigned());
  EXPECT_EQ(j["name"], "p");
  EXPECT_EQ(j["outer"]["corner_m"], nlohmann::json::array({1.0, 2.0}));
  EXPECT_EQ(j["outer"]["gate"], 4.0);
  EXPECT_EQ(j["colour"], "green");
  EXPECT_FALSE(j["outer"].contains("items"));  // Listed: its caller writes it
  p.gate.reset();
  EXPECT_FALSE(ParamsJson(TableOf(p))["outer"].contains("gate"));
}

TEST(ParamTableKeys, SectionsAndKeysInFirstMentionOrder) {
  Params p;
  const ParamTable t = TableOf(p);
  EXPECT_EQ(ChildSections(t, ""), (std::vector<std::string>{"outer"}));
  EXPECT_EQ(ChildSections(t, "outer"), (std::vector<std::string>{"outer.inner"}));
  EXPECT_EQ(KnownKeys(t, "outer"), (std::vector<std::string>{"limit_m", "fraction", "corner_m",
                                                             "gate", "items", "inner"}));
}

}  // namespace
}  // namespace slamkit::config
