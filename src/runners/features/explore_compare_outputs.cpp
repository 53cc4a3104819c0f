// The comparison's files: compare.md (the table), compare.csv (the runs), metrics.json.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/features/explore_compare.hpp"

namespace slamkit {
namespace {

nlohmann::json SpreadJson(const Spread& s) {
  return {{"mean", s.mean}, {"sd", s.sd()}, {"min", s.min}, {"max", s.max}};
}

// JSON null for a missing figure (a policy whose steps never had anything to reduce).
nlohmann::json Optional(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

std::string Fixed(const std::optional<double>& v, int digits) {
  return v ? fmt::format("{:.{}f}", *v, digits) : std::string("—");
}

double RunAccuracy(const CompareRun& r) {
  return r.accuracy_steps > 0 ? r.accuracy_sum / r.accuracy_steps
                              : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json SummaryJson(const ComparePolicySummary& s) {
  return {{"policy", SelectionKindName(s.policy)},
          {"runs", s.runs},
          {"slam_time_total_s", SpreadJson(s.slam_time_total_s)},
          {"slam_time_max_mean_s", s.slam_time_max_mean_s},
          {"slam_time_max_s", s.slam_time_max_s},
          {"open_loop_time_s", SpreadJson(s.open_loop_time_s)},
          {"accuracy_step_mean", Optional(s.accuracy_step_mean)},
          {"accuracy_run_mean", Optional(s.accuracy_run_mean)},
          {"anees", s.anees},
          {"anees_runs", s.anees_runs},
          {"anees_band", {s.band.lo, s.band.hi}},
          {"anees_in_band", s.anees_in_band},
          {"anees_mean", s.anees_mean},
          {"mean_error_m", SpreadJson(s.mean_error_m)},
          {"final_error_m", SpreadJson(s.final_error_m)},
          {"odometry_mean_error_m", SpreadJson(s.odometry_mean_error_m)},
          {"odometry_final_error_m", SpreadJson(s.odometry_final_error_m)},
          {"lines", SpreadJson(s.lines)},
          {"corners", SpreadJson(s.corners)},
          {"steps", SpreadJson(s.steps)},
          {"elapsed_s", SpreadJson(s.elapsed_s)},
          {"wall_time_s", SpreadJson(s.wall_time_s)}};
}

nlohmann::json RunJson(const CompareRun& r) {
  nlohmann::json j = ExploreFiguresJson(r.figures);
  j["policy"] = SelectionKindName(r.policy);
  j["seed"] = r.seed;
  j["accuracy_mean"] = r.accuracy_steps > 0 ? nlohmann::json(RunAccuracy(r)) : nullptr;
  j["accuracy_steps"] = r.accuracy_steps;
  return j;
}

nlohmann::json CompareMetrics(const ExploreCompareResult& result, const ExplorationConfig& config,
                              const ExploreCompareParams& params, const std::string& command) {
  nlohmann::json j = {{"params", ExplorationConfigJson(config)},
                      {"command", command},
                      {"seeds", params.seeds},
                      {"wall_time_s", result.wall_time_s}};
  for (const SelectionKind p : params.policies) j["policies"].push_back(SelectionKindName(p));
  j["summary"] = nlohmann::json::array();
  for (const ComparePolicySummary& s : result.policies) j["summary"].push_back(SummaryJson(s));
  j["savings"] = nlohmann::json::array();
  for (const CovarianceSavings& s : result.savings) {
    j["savings"].push_back({{"against", SelectionKindName(s.against)},
                            {"of_means_pct", s.of_means_pct},
                            {"min_pct", s.min_pct},
                            {"max_pct", s.max_pct}});
  }
  j["runs"] = nlohmann::json::array();
  for (const CompareRun& r : result.runs) j["runs"].push_back(RunJson(r));
  return j;
}

void WriteCompareCsv(const std::filesystem::path& path, const std::vector<CompareRun>& runs) {
  WriteFileAtomically(path, [&runs](std::ostream& os) {
    os << "policy,seed,steps,elapsed_s,slam_time_total_s,slam_time_max_s,open_loop_time_s,"
          "accuracy_mean,mean_nees,mean_error_m,final_error_m,odometry_mean_error_m,"
          "odometry_final_error_m,lines,corners,final_mode,wall_time_s\n";
    for (const CompareRun& r : runs) {
      const double accuracy = RunAccuracy(r);
      os << fmt::format(
          "{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{},{:.17g},{:.17g},{:.17g},"
          "{:.17g},{:.17g},{},{},{},{:.6f}\n",
          SelectionKindName(r.policy), r.seed, r.figures.steps, r.figures.elapsed_s,
          r.figures.slam_time_total_s, r.figures.slam_time_max_s, r.figures.open_loop_time_s,
          std::isnan(accuracy) ? std::string() : fmt::format("{:.17g}", accuracy),
          r.figures.mean_nees, r.figures.mean_error_m, r.figures.final_error_m,
          r.figures.odometry_mean_error_m, r.figures.odometry_final_error_m, r.figures.lines,
          r.figures.corners, ExplorerModeName(r.figures.final_mode), r.figures.wall_time_s);
    }
  });
}

std::string TableRow(const ComparePolicySummary& s) {
  return fmt::format(
      "| {} | {} | {:.3f} ± {:.3f} ({:.3f}–{:.3f}) | {:.3f} / {:.3f} | {:.1f} ± {:.1f} | "
      "{} / {} | {:.2f} ({:.0f} %) | {:.3f} / {:.3f} | {:.3f} / {:.3f} | {:.1f} | {:.1f} | "
      "{:.0f} | {:.1f} | {:.1f} |\n",
      SelectionKindName(s.policy), s.runs, s.slam_time_total_s.mean, s.slam_time_total_s.sd(),
      s.slam_time_total_s.min, s.slam_time_total_s.max, 1e3 * s.slam_time_max_mean_s,
      1e3 * s.slam_time_max_s, s.open_loop_time_s.mean, s.open_loop_time_s.sd(),
      Fixed(s.accuracy_step_mean, 3), Fixed(s.accuracy_run_mean, 3), s.anees_mean,
      100.0 * s.anees_in_band, s.mean_error_m.mean, s.final_error_m.mean,
      s.odometry_mean_error_m.mean, s.odometry_final_error_m.mean, s.lines.mean, s.corners.mean,
      s.steps.mean, s.elapsed_s.mean, s.wall_time_s.mean);
}

}  // namespace

std::string ExploreCompareMarkdown(const ExploreCompareResult& result,
                                   const ExplorationConfig& config, const std::string& command) {
  std::ostringstream md;
  const int runs = result.policies.empty() ? 0 : result.policies.front().runs;
  md << fmt::format("# Selection policies compared (SPEC S1), {} seeds per policy\n\n", runs);
  md << "| policy | runs | SLAM time total [s]: mean ± sd (min–max) | step max [ms]: mean / max "
        "| open-loop [s] | accuracy Eq. 24: steps / runs | ANEES (steps in band) "
        "| error [m]: mean / final | odometry error [m]: mean / final | lines | corners "
        "| steps | simulated [s] | wall [s] |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ComparePolicySummary& s : result.policies) md << TableRow(s);
  md << "\nMeans over the seeds. ANEES: pose NEES (3 dof) averaged over the runs at each step "
        "while at least half of them are running, each step against the 95 % band for its "
        "number of runs";
  if (!result.policies.empty()) {
    const ChiSquareBand& b = result.policies.front().band;
    md << fmt::format(" ([{:.2f}, {:.2f}] for all {})", b.lo, b.hi, runs);
  }
  md << ".\n";
  md << (config.run.timing == SlamTiming::kModelledCost
             ? fmt::format("SLAM time modelled: each step's counted work at {:.3g} flop/s.\n\n",
                           config.slam.flops_per_second)
             : std::string("SLAM time measured (wall clock), runs one at a time, without the "
                           "accuracy diagnostics (their extra full update would be timed "
                           "too).\n\n"));
  for (const CovarianceSavings& s : result.savings) {
    md << fmt::format(
        "- covariance vs {}: {:.1f} % less accumulated SLAM time (of the means; seed by seed "
        "{:.1f} % to {:.1f} %)\n",
        SelectionKindName(s.against), s.of_means_pct, s.min_pct, s.max_pct);
  }
  md << fmt::format("\nWall time of the comparison: {:.1f} s.\n\n```sh\n{}\n```\n",
                    result.wall_time_s, command);
  return md.str();
}

void WriteExploreCompareOutputs(const std::filesystem::path& dir,
                                const ExploreCompareResult& result, const ExplorationConfig& config,
                                const ExploreCompareParams& params, const std::string& command) {
  WriteFileAtomically(dir / "compare.md", ExploreCompareMarkdown(result, config, command));
  WriteCompareCsv(dir / "compare.csv", result.runs);
  WriteJson(dir / "metrics.json", CompareMetrics(result, config, params, command));
}

}  // namespace slamkit
