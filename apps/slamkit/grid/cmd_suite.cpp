// `slamkit suite`: the grid filter on every log of a manifest and every seed, each run a
// `slamkit grid` child process (so that each has its own peak memory, and a run that fails or
// crashes costs only itself), as many at once as --jobs; then the summary and maps.png, the
// contact sheet of every run's map.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/commands.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "grid/suite_sheet.hpp"
#include "common/progress.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/map_reader.hpp"
#include "slamkit/io/trajectory_reader.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/grid/suite_manifest.hpp"
#include "slamkit/runners/common/shard.hpp"
#include "slamkit/runners/grid/suite_summary.hpp"

extern char** environ;

namespace slamkit::app {
namespace {

namespace fs = std::filesystem;

struct SuiteOptions {
  std::string manifest;
  std::string root;
  std::string seeds = "1";
  int particles = 0;  // 0: the grid command's default
  int max_scans = 0;
  int jobs = 0;       // 0: UsableCpuCount
  std::string config;  // the grid filter's parameters, for every run
  std::string logs;    // comma-separated names: only these logs (empty: all)
  std::string backend = "rbpf";  // rbpf, graph or both
  std::string shard;             // K/N; empty: every run
  std::string out;
};

struct SuiteJob {
  const SuiteLog* log = nullptr;
  std::string backend;
  std::uint64_t seed = 0;
  fs::path out;       // the run's --out
  fs::path console;   // its stdout and stderr
  std::vector<std::string> args;
};

// The child's command line; `threads` of it, so that the runs at once share the CPUs.
std::vector<std::string> GridArgs(const SuiteOptions& o, const SuiteJob& job, int threads) {
  const SuiteLog& log = *job.log;
  std::vector<std::string> a = {"slamkit", "grid", "--log", log.log.string(), "--seed",
                                std::to_string(job.seed), "--threads", std::to_string(threads),
                                "--out", job.out.string()};
  if (job.backend != "rbpf" || o.backend != "rbpf") a.insert(a.end(), {"--backend", job.backend});
  if (!o.config.empty()) a.insert(a.end(), {"--config", fs::absolute(o.config).string()});
  if (o.particles > 0) a.insert(a.end(), {"--particles", std::to_string(o.particles)});
  if (o.max_scans > 0) a.insert(a.end(), {"--max-scans", std::to_string(o.max_scans)});
  if (!log.relations.empty()) a.insert(a.end(), {"--relations", log.relations.string()});
  if (!log.reference.empty()) {
    a.insert(a.end(), {"--reference", log.reference.string(), "--pair-by",
                       log.pair_by == PairBy::kIndex ? "index" : "time"});
  }
  if (log.reference_from_log) a.push_back("--reference-from-log");
  return a;
}

// Starts `job` as a child running this executable; its output goes to job.console.
pid_t Spawn(const SuiteJob& job) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, job.console.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> argv;
  for (const std::string& a : job.args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw std::runtime_error(fmt::format("cannot start a grid run: {}", std::strerror(rc)));
  }
  return pid;
}

// The last line of the run's console output that says "error" (what a failed run reported).
std::string FailureOf(const SuiteJob& job, int status) {
  std::ifstream in(job.console);
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.find("error") != std::string::npos) last = line;
  }
  const std::string how = WIFSIGNALED(status) ? fmt::format("killed by signal {}", WTERMSIG(status))
                                              : fmt::format("exit {}", WEXITSTATUS(status));
  return last.empty() ? how : fmt::format("{}: {}", how, last);
}

SuiteRunRecord Record(const SuiteJob& job, int status, const rusage& usage, double wall_s) {
  SuiteRunRecord r;
  r.log = job.log->name;
  r.backend = job.backend;
  r.seed = job.seed;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.wall_time_s = wall_s;
  r.peak_rss_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: KiB
  std::ifstream metrics(job.out / "metrics.json");
  if (metrics) r.metrics = nlohmann::json::parse(metrics, nullptr, /*allow_exceptions=*/false);
  if (r.exit_code != 0 || !r.metrics.is_object()) r.failure = FailureOf(job, status);
  return r;
}

// Biggest log first (its file size as the measure), so that the longest run does not start
// last and leave the other CPUs idle while it finishes.
std::vector<std::size_t> StartOrder(const std::vector<SuiteJob>& all) {
  std::vector<std::uintmax_t> size(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    std::error_code ec;
    size[i] = fs::file_size(all[i].log->log, ec);
  }
  std::vector<std::size_t> order(all.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return size[a] > size[b]; });
  return order;
}

// Runs every job, `jobs` at a time, biggest first; records in the jobs' order.
std::vector<SuiteRunRecord> RunJobs(const std::vector<SuiteJob>& all, int jobs) {
  using Clock = std::chrono::steady_clock;
  const std::vector<std::size_t> order = StartOrder(all);
  std::vector<SuiteRunRecord> records(all.size());
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  Progress progress("runs", static_cast<int>(all.size()));
  std::size_t next = 0;
  int done = 0;
  while (next < all.size() || !running.empty()) {
    while (next < all.size() && static_cast<int>(running.size()) < jobs) {
      running[Spawn(all[order[next]])] = {order[next], Clock::now()};
      ++next;
    }
    int status = 0;
    rusage usage{};
    const pid_t pid = wait4(-1, &status, 0, &usage);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("waiting for a grid run: {}", std::strerror(errno)));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const auto [index, start] = it->second;
    running.erase(it);
    records[index] = Record(all[index], status, usage,
                            std::chrono::duration<double>(Clock::now() - start).count());
    progress.Update(++done);
  }
  return records;
}

// The manifest's logs named in `names` ("a,b"; empty: all of them), in the manifest's order.
std::vector<const SuiteLog*> SelectLogs(const SuiteManifest& manifest, const std::string& names,
                                        const std::string& manifest_path) {
  std::vector<const SuiteLog*> out;
  std::set<std::string> wanted;
  for (std::size_t start = 0; !names.empty() && start <= names.size();) {
    const std::size_t comma = std::min(names.find(',', start), names.size());
    wanted.insert(names.substr(start, comma - start));
    start = comma + 1;
  }
  std::string known;
  for (const SuiteLog& log : manifest.logs) {
    known += (known.empty() ? "" : ", ") + log.name;
    if (names.empty() || wanted.erase(log.name) > 0) out.push_back(&log);
  }
  if (!wanted.empty()) {
    throw InputError(fmt::format("--logs: no log '{}' in {} (its logs: {})", *wanted.begin(),
                                 manifest_path, known));
  }
  return out;
}

// Every run of the study, in its order: each log with the particle filter for every seed and,
// after them, with the graph once (it draws no random numbers: a seed changes nothing).
std::vector<SuiteJob> AllJobs(const SuiteOptions& o, const std::vector<const SuiteLog*>& logs,
                              const std::vector<std::uint64_t>& seeds, const fs::path& dir) {
  std::vector<SuiteJob> jobs;
  for (const SuiteLog* log : logs) {
    const fs::path runs = dir / "runs" / log->name;
    if (o.backend != "graph") {
      for (std::uint64_t seed : seeds) {
        jobs.push_back({log, "rbpf", seed, runs / fmt::format("seed_{}", seed),
                        runs / fmt::format("seed_{}.txt", seed), {}});
      }
    }
    if (o.backend != "rbpf") {
      jobs.push_back({log, "graph", seeds.front(), runs / "graph", runs / "graph.txt", {}});
    }
  }
  return jobs;
}

// summary.json's "shard": which part of which study this output holds (slamkit merge checks it).
nlohmann::json ShardJson(const SuiteOptions& o, const Shard& shard, const ShardRange& range,
                         const std::vector<SuiteJob>& jobs, const std::vector<std::uint64_t>& seeds) {
  nlohmann::json names = nlohmann::json::array();
  for (const SuiteJob& job : jobs) {
    names.push_back(fmt::format("{}/{}/{}", job.log->name, job.backend, job.seed));
  }
  return {{"index", shard.index}, {"count", shard.count}, {"first_job", range.begin},
          {"end_job", range.end}, {"jobs", names},
          {"study", {{"manifest", o.manifest}, {"seeds", seeds}, {"backend", o.backend},
                     {"logs", o.logs}, {"particles", o.particles}, {"max_scans", o.max_scans},
                     {"config", o.config}}}};
}

int RunSuiteCommand(const SuiteOptions& o) {
  const SuiteManifest manifest = LoadSuiteManifest(o.manifest, o.root);
  const std::vector<const SuiteLog*> logs = SelectLogs(manifest, o.logs, o.manifest);
  const std::vector<std::uint64_t> seeds = ParseSeeds(o.seeds);
  const Shard shard = o.shard.empty() ? Shard{} : ParseShard(o.shard);
  OutputDir output(o.out);
  const fs::path& dir = output.staging();
  const std::vector<SuiteJob> all = AllJobs(o, logs, seeds, dir);
  if (shard.count > static_cast<int>(all.size())) {
    throw CLI::ValidationError("--shard", fmt::format("{} parts of {} runs: N must be at most "
                                                      "the number of runs", shard.count, all.size()));
  }
  const ShardRange range = RangeOfShard(static_cast<int>(all.size()), shard);
  std::vector<SuiteJob> jobs(all.begin() + range.begin, all.begin() + range.end);
  const int parallel = o.jobs > 0 ? o.jobs : UsableCpuCount();
  const int threads = std::max(1, UsableCpuCount() / parallel);
  for (SuiteJob& job : jobs) {
    fs::create_directories(job.out.parent_path());
    job.args = GridArgs(o, job, threads);
  }
  const std::vector<SuiteRunRecord> records = RunJobs(jobs, parallel);
  const std::string title = fmt::format("slamkit suite: {}", o.manifest);
  WriteSuiteSummary(dir, title, records,
                    shard.whole() ? nlohmann::json() : ShardJson(o, shard, range, all, seeds));
  WriteSuiteContactSheet(dir, records, title);
  output.Commit();
  int failed = 0;
  for (const SuiteRunRecord& r : records) failed += r.failure.empty() ? 0 : 1;
  const std::string graph_runs = o.backend == "rbpf" ? "" : " + 1 graph";
  const std::string part =
      shard.whole() ? "" : fmt::format(" of shard {}/{}", shard.index, shard.count);
  fmt::print("{} runs{} ({} logs x {} seeds{}), {} failed\nwrote {}\n", records.size(), part,
             logs.size(), o.backend == "graph" ? 0 : seeds.size(), graph_runs, failed, o.out);
  return failed > 0 ? 1 : 0;
}

}  // namespace

void RegisterSuite(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SuiteOptions>();
  CLI::App* cmd = app.add_subcommand(
      "suite", "the grid filter on every log of a suite manifest and every seed, with a summary");
  AddExamples(cmd, {
               "--manifest configs/carmen_suite.yaml --logs freiburg-101,csail --seeds 1-2 --out out/suite_small",
               "--manifest configs/carmen_suite.yaml --seeds 1-5 --backend both --out out/suite"});
  cmd->add_option("--manifest", o->manifest, "suite manifest (configs/carmen_suite.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_option("--seeds", o->seeds, "seeds: 1-5, 1,3,7 or 2")->capture_default_str();
  cmd->add_option("--particles", o->particles, "particles (default: the grid command's)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--config", o->config, "the grid filter's parameters for every run "
                                         "(configs/grid.yaml; see slamkit grid --config)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--backend", o->backend,
                  "rbpf: the particle filter for every seed; graph: the pose graph once per log "
                  "(it draws no random numbers); both: each log with both, side by side")
      ->check(CLI::IsMember({"rbpf", "graph", "both"}))->capture_default_str();
  cmd->add_option("--logs", o->logs, "only these logs of the manifest: NAME[,NAME...]");
  cmd->add_option("--shard", o->shard,
                  "K/N: run only the K-th of N contiguous parts of the log x seed runs (slamkit "
                  "merge joins the N output folders into the unsharded suite's)")
      ->check(ShardText());
  cmd->add_option("--max-scans", o->max_scans, "use only each log's first N scans (0: all)")
      ->check(NonNegativeNumber());
  cmd->add_option("--jobs", o->jobs, "runs at once (0: the CPUs this process may use)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--root", o->root, "the folder the manifest's paths are relative to "
                                     "(default: the manifest's `root`)")
      ->check(CLI::ExistingDirectory);
  cmd->callback([o, &exit_code] { exit_code = RunSuiteCommand(*o); });
}

}  // namespace slamkit::app
