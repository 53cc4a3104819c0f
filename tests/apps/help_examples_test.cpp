// Issue 31 part 6: every subcommand's --help ends with examples that run as written from the
// repository root. Each is run here with --dry-run (options parsed, the files they name checked,
// nothing run) from a copy of the root's layout; scripts/analysis/help_examples.sh runs them all.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> Words(const std::string& line) {
  std::vector<std::string> words;
  std::istringstream in(line.substr(0, line.find(" #")));  // a trailing shell comment
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// The subcommands `slamkit --help` lists.
std::vector<std::string> Subcommands() {
  std::vector<std::string> names;
  bool listing = false;
  for (const std::string& line : Lines(RunCli("--help").output)) {
    if (line.rfind("Subcommands:", 0) == 0) listing = true;
    if (!listing || line.size() < 3 || line[0] != ' ' || line[2] == ' ') continue;
    names.push_back(Words(line).front());
  }
  return names;
}

// The lines under "Examples (from the repository root):" in `name --help`.
std::vector<std::string> Examples(const std::string& name) {
  const CliResult help = RunCli(name + " --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  std::vector<std::string> examples;
  bool listing = false;
  for (const std::string& line : Lines(help.output)) {
    if (line == "Examples (from the repository root):") {
      listing = true;
    } else if (listing && line.rfind("  ", 0) == 0) {
      examples.push_back(line.substr(2));
    } else if (listing && !line.empty()) {
      ADD_FAILURE() << name << ": text after the examples: " << line;
    }
  }
  return examples;
}

// The repository root's layout: configs and examples, and ../shared beside it.
fs::path MirrorRoot() {
  const fs::path top = FreshDir("help_examples");
  const fs::path root = top / "repo";
  fs::create_directories(root);
  const fs::path source = SLAMKIT_SOURCE_DIR;
  for (const char* folder : {"configs", "examples"}) fs::create_directory_symlink(source / folder, root / folder);
  fs::create_directory_symlink(fs::path(SLAMKIT_DATASETS_DIR).parent_path(), top / "shared");
  return root;
}

TEST(HelpExamples, EveryCommandEndsWithExamplesThatParseAndFindTheirFiles) {
  if (!fs::exists(fs::path(SLAMKIT_DATASETS_DIR) / "carmen" / "intel.clf")) {
    GTEST_SKIP() << "no datasets beside the repository";
  }
  const std::vector<std::string> names = Subcommands();
  ASSERT_GE(names.size(), 14u);
  std::vector<std::vector<std::string>> runs;
  std::set<std::string> written;  // every example's --out
  for (const std::string& name : names) {
    const std::vector<std::string> examples = Examples(name);
    EXPECT_GE(examples.size(), 1u) << name;
    EXPECT_LE(examples.size(), 2u) << name;
    for (const std::string& example : examples) {
      std::vector<std::string> words = Words(example);
      ASSERT_GE(words.size(), 3u) << example;
      EXPECT_EQ(words[0], CliPath()) << example;  // the program as it was invoked
      EXPECT_EQ(words[1], name) << example;
      for (std::size_t i = 2; i + 1 < words.size(); ++i) {
        if (words[i] == "--out") written.insert(words[i + 1]);
      }
      runs.push_back(words);
    }
  }
  const fs::path root = MirrorRoot();
  std::set<std::string> read;  // the outputs that other examples read, made here
  for (const auto& words : runs) {
    // An input under out/ is what another example writes: a file in its folder (mapdiff and
    // localize read grid's map) or the folder itself (merge reads mc's shards).
    for (std::size_t i = 2; i < words.size(); ++i) {
      if (words[i].rfind("out/", 0) != 0 || words[i - 1] == "--out") continue;
      const bool folder = written.count(words[i]) > 0;
      const std::string dir = folder ? words[i] : fs::path(words[i]).parent_path().string();
      EXPECT_TRUE(written.count(dir)) << words[i] << " is written by no example";
      read.insert(dir);
      fs::create_directories(root / dir);
      if (!folder) std::ofstream(root / words[i]) << "";
    }
  }
  for (const auto& words : runs) {
    std::string args = "--dry-run";
    for (std::size_t i = 1; i < words.size(); ++i) args += " " + words[i];
    const CliResult r = RunShell(args + " 2>&1", "cd '" + root.string() + "' && ");
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("dry run"), std::string::npos) << r.output;
  }
  for (const std::string& out : written) {
    if (read.count(out)) continue;
    EXPECT_FALSE(fs::exists(root / out)) << out << ": a dry run wrote it";
  }
}

TEST(HelpExamples, ADryRunStillRejectsAMissingFile) {
  const fs::path dir = FreshDir("dry_run_missing");
  const CliResult r = RunCli("--dry-run grid --log " + (dir / "none.clf").string() + " --out " +
                             (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--log"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace slamkit::testing
