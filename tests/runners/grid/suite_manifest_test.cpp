#include "slamkit/runners/grid/suite_manifest.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

TEST(SuiteManifest, TheShippedSuiteListsEveryCarmenLogWithItsReference) {
  const fs::path carmen = fs::path(SLAMKIT_DATASETS_DIR) / "carmen";
  if (!fs::exists(carmen / "suite")) GTEST_SKIP() << "no " << carmen;
  const SuiteManifest m =
      LoadSuiteManifest(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "carmen_suite.yaml");
  ASSERT_EQ(m.logs.size(), 7u);
  EXPECT_EQ(m.logs[0].name, "intel");
  EXPECT_FALSE(m.logs[0].relations.empty());
  for (const SuiteLog& log : m.logs) {
    EXPECT_TRUE(fs::exists(log.log)) << log.name;
    if (log.name != "intel") {
      EXPECT_TRUE(fs::exists(log.reference)) << log.name;
    }
  }
  // The logs whose stamps cannot pair poses (datasets README) pair by index.
  for (const SuiteLog& log : m.logs) {
    const bool by_index = log.name == "belgioioso" || log.name == "csail" ||
                          log.name == "freiburg-campus";
    EXPECT_EQ(log.pair_by, by_index ? PairBy::kIndex : PairBy::kTime) << log.name;
  }
}

class SuiteManifestFile : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    WriteFile("a.log", "");
    WriteFile("a.ref", "");
  }
  std::string ErrorOf(const std::string& yaml) const {
    const fs::path path = WriteFile("suite.yaml", yaml);
    return testing::InputErrorOf([&] { LoadSuiteManifest(path); });
  }
};

TEST_F(SuiteManifestFile, PathsAreRelativeToTheRootAndTheRootToTheFile) {
  fs::create_directories(dir_ / "data");
  WriteFile("data/b.log", "");
  const fs::path path = WriteFile("suite.yaml", "root: data\nlogs:\n  - {name: b, log: b.log}\n");
  const SuiteManifest m = LoadSuiteManifest(path);
  ASSERT_EQ(m.logs.size(), 1u);
  EXPECT_EQ(m.logs[0].log, dir_ / "data" / "b.log");
  EXPECT_TRUE(m.logs[0].reference.empty());
  // --root replaces the file's root.
  EXPECT_EQ(LoadSuiteManifest(path, dir_ / "data").logs[0].log, dir_ / "data" / "b.log");
  EXPECT_THROW(LoadSuiteManifest(path, dir_ / "elsewhere"), InputError);
}

TEST_F(SuiteManifestFile, MistakesNameTheFileLineAndKey) {
  struct Case {
    std::string yaml, part;
  };
  const Case cases[] = {
      {"logs:\n  - {name: a, log: missing.log}\n", ":2: key 'logs[0].log': no such file"},
      {"logs:\n  - {name: a, log: a.log, reference: a.ref, pair_by: stamp}\n",
       "key 'logs[0].pair_by': expected one of time, index, got 'stamp'"},
      {"logs:\n  - {name: a, log: a.log, pair_by: index}\n", "there is no `reference`"},
      {"logs:\n  - {name: a, log: a.log}\n  - {name: a, log: a.log}\n",
       ":3: key 'logs[1].name': 'a' names another log already"},
      {"logs:\n  - {name: a, log: a.log, refrence: a.ref}\n", "refrence"},
      {"logs:\n  - {log: a.log}\n", "key 'logs[0].name': required"},
      {"logs:\n  - {name: a/b, log: a.log}\n", "without '/'"},
      {"logs:\n  - {name: a}\n", "key 'logs[0].log': required"},
      {"logs:\n  - {name: a, log: a.log, reference: a.ref, reference_from_log: true}\n",
       "not both"},
      {"logs: []\n", "key 'logs': required"},
      {"root: .\n", "key 'logs': required"}};
  for (const Case& c : cases) {
    const std::string message = ErrorOf(c.yaml);
    EXPECT_NE(message.find("suite.yaml"), std::string::npos) << c.yaml << message;
    EXPECT_NE(message.find(c.part), std::string::npos) << c.yaml << "\n" << message;
  }
}

}  // namespace
}  // namespace slamkit
