// The command line's contract with its caller: closed or full streams, unusable output folders,
// refused options named in words, progress lines, thread counts and outputs replaced whole.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::kShortScenario;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

TEST(Cli, ClosedOrFullStderrDoesNotAbort) {
  const fs::path dir = FreshDir("stderr_closed");
  int k = 0;
  for (const char* redirect : {"2>&-", "2>/dev/full"}) {
    for (const std::string& command :
         {"mc --config " + kShortScenario + " --runs 3 --no-figures --out ",
          std::string("gridsim --particles 5 --max-steps 300 --out ")}) {
      const fs::path out = dir / std::to_string(k++);
      const auto r = testing::RunShell(command + out.string() + " " + redirect);
      EXPECT_EQ(r.exit_code, 0) << command << redirect << "\n" << r.output;
      EXPECT_NE(r.output.find("wrote"), std::string::npos) << command << redirect;
      EXPECT_TRUE(fs::exists(out / "metrics.json")) << command << redirect;
    }
  }
  // An error message to a closed or full stderr: still exit 2, no abort.
  std::ofstream(dir / "bad.yaml") << "name: bad\nsensor:\n  max_range_m: fast\n";
  for (const char* redirect : {"2>&-", "2>/dev/full"}) {
    const auto r = testing::RunShell("mc --config " + (dir / "bad.yaml").string() + " --out " +
                                     (dir / "x").string() + " " + redirect);
    EXPECT_EQ(r.exit_code, 2) << redirect << "\n" << r.output;
  }
}

// Issue 8 item 20: a summary that cannot be written to stdout is a failed run (exit 1, said on
// stderr); the output files stay.
TEST(Cli, ClosedOrFullStdoutExitsOne) {
  const fs::path dir = FreshDir("stdout_full");
  int k = 0;
  for (const char* redirect : {"2>&1 >/dev/full", "2>&1 >&-"}) {
    const fs::path out = dir / std::to_string(k++);
    const auto r = testing::RunShell("mc --config " + kShortScenario +
                                     " --runs 2 --no-figures --out " + out.string() + " " +
                                     redirect);
    EXPECT_EQ(r.exit_code, 1) << redirect << "\n" << r.output;
    EXPECT_NE(r.output.find("stdout"), std::string::npos) << redirect << "\n" << r.output;
    EXPECT_TRUE(fs::exists(out / "metrics.json")) << redirect;
  }
}

// Issue 8 item 15: an --out that cannot be the output directory fails (exit 2, naming it)
// before the run.
TEST(Cli, UnusableOutExitsTwoBeforeTheRun) {
  const fs::path dir = FreshDir("bad_out");
  std::ofstream(dir / "a_file") << "x\n";
  const std::pair<std::string, std::string> cases[] = {
      {"/proc/x", "/proc/x"},
      {(dir / "a_file").string(), "a_file"},
      {(dir / "a_file" / "sub").string(), "a_file"},
      {"''", "--out"}};
  for (const auto& [out, named] : cases) {
    for (const std::string& command :
         {"mc --config " + kShortScenario + " --runs 2 --no-figures",
          std::string("gridsim --particles 5 --max-steps 300")}) {
      const auto r = RunCli(command + " --out " + out);
      EXPECT_EQ(r.exit_code, 2) << command << " --out " << out << "\n" << r.output;
      EXPECT_NE(r.output.find(named), std::string::npos) << out << "\n" << r.output;
      EXPECT_EQ(r.output.find("runs:"), std::string::npos) << out << ": ran\n" << r.output;
      EXPECT_EQ(r.output.find("scans:"), std::string::npos) << out << ": ran\n" << r.output;
    }
  }
  EXPECT_EQ(ReadText(dir / "a_file"), "x\n");
}

// Issue 8 item 16: a range check says its range in words, not as 309 digits.
TEST(Cli, RangeErrorsSayTheRangeInWords) {
  const fs::path dir = FreshDir("range_words");
  const std::string out = " --out " + (dir / "out").string();
  const std::pair<std::string, std::string> cases[] = {
      {"gridsim --resolution 0", "must be > 0"},
      {"gridsim --usable-range -1", "must be > 0"},
      {"gridsim --srr -0.1", "must be >= 0"},
      {"gridsim --max-steps -3", "must be >= 0"},
      {"gridsim --odom-sigma-v nan", "must be >= 0"},
      {"grid --log " + kShortScenario + " --max-range 0", "must be > 0"},
      {"run --isam " + kShortScenario + " --gate-chi2 0", "must be > 0"}};
  for (const auto& [args, words] : cases) {
    const auto r = RunCli(args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("1797693"), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Issue 8 item 10: a negative seed is refused, not wrapped to 2^64 - 1.
TEST(Cli, NegativeSeedIsRefused) {
  const fs::path dir = FreshDir("negative_seed");
  const std::string out = " --out " + (dir / "out").string();
  const std::string cases[] = {
      "mc --config " + kShortScenario + " --runs 1 --seed -1",
      "gridsim --seed -1", "gridsim --sim-seed -2"};
  for (const std::string& args : cases) {
    const auto r = RunCli(args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("must be a whole number from 0"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Issue 8 item 17: progress lines show the elapsed time, and no rate before time has passed to
// measure one (the first line said "1250000000 scans/s").
TEST(Cli, FirstProgressLineHasElapsedTimeAndNoRate) {
  const fs::path dir = FreshDir("progress_rate");
  const auto r = RunCli("gridsim --particles 5 --max-steps 300 --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::size_t at = r.output.find("scans: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string first = r.output.substr(at, r.output.find('\n', at) - at);
  EXPECT_NE(first.find("elapsed"), std::string::npos) << first;
  EXPECT_EQ(first.find("/s"), std::string::npos) << first;
}

// Issue 8 item 18: --threads 0 means the CPUs of the process's affinity mask (TBB warned about
// 0 workers when it was hardware_concurrency under `taskset -c 0`).
TEST(Cli, ThreadsZeroFollowsTheAffinityMask) {
  const fs::path dir = FreshDir("threads_mask");
  const auto r = testing::RunShell("mc --config " + kShortScenario + " --runs 40 --threads 0 --no-figures --out " +
                                       (dir / "out").string() + " 2>&1",
                                   "taskset -c 0 ");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("TBB"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("arning"), std::string::npos) << r.output;
}

// Issue 8 items 14 and 13: a run replaces its --out as a whole (written beside it, then renamed):
// a smaller run leaves none of a larger one's files, a directory of other files is refused, and
// a run interrupted by SIGINT leaves the old output as it was.
TEST(Cli, OutputReplacesTheOldOneAsAWhole) {
  const fs::path dir = FreshDir("out_whole");
  const fs::path out = dir / "out";
  const std::string mc = "mc --config " + kShortScenario + " --no-figures --threads 1 --out " + out.string();
  ASSERT_EQ(RunCli(mc + " --runs 4").exit_code, 0);
  ASSERT_TRUE(fs::exists(out / "run_3"));
  const std::string old_metrics = ReadText(out / "metrics.json");

  // SIGINT in the middle of a long run: the old output stays, whole.
  const std::string cli = testing::CliPath();
  const std::string config = kShortScenario, out_arg = out.string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::signal(SIGINT, SIG_DFL);
    const int null_fd = open("/dev/null", O_WRONLY);
    dup2(null_fd, 1);
    dup2(null_fd, 2);
    execl(cli.c_str(), cli.c_str(), "mc", "--config", config.c_str(), "--no-figures", "--threads",
          "1", "--runs", "100000", "--seed", "9", "--out", out_arg.c_str(), nullptr);
    _exit(127);
  }
  sleep(1);
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(ReadText(out / "metrics.json"), old_metrics);
  EXPECT_TRUE(fs::exists(out / "run_3"));

  const auto r = RunCli(mc + " --runs 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "run_1"));
  EXPECT_FALSE(fs::exists(out / "run_2"));
  EXPECT_FALSE(fs::exists(out / "run_3"));
  EXPECT_EQ(nlohmann::json::parse(ReadText(out / "metrics.json"))["runs"], 2);
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    // Only the interrupted run's hidden folder may be left beside it.
    if (name != "out") {
      EXPECT_EQ(name.rfind(".out.partial-", 0), 0u) << name;
    }
  }

  // A directory with other files is not replaced.
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "notes.txt") << "keep\n";
  const auto refused = RunCli("mc --config " + kShortScenario + " --runs 2 --no-figures --out " +
                              (dir / "mine").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("mine"), std::string::npos) << refused.output;
  EXPECT_EQ(ReadText(dir / "mine" / "notes.txt"), "keep\n");
}

}  // namespace
}  // namespace slamkit
