#include "slamkit/runners/landmark/study.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>

#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

struct MethodSpec {
  const char* key;
  FilterKind filter;
  PlannerKind planner;
};

// The seed's order (its tables' rows); the FastSLAM row runs StudyParams::fastslam.
constexpr MethodSpec kMethods[] = {{"ekf_slam", FilterKind::kEkf, PlannerKind::kRoute},
                                   {"fastslam", FilterKind::kFastSlam2, PlannerKind::kRoute},
                                   {"swslam", FilterKind::kEkf, PlannerKind::kSwslam}};
constexpr int kFastSlam = 1;
constexpr int kSwslam = 2;

FilterKind FilterOf(int index, const StudyParams& params) {
  return index == kFastSlam ? params.fastslam : kMethods[index].filter;
}

// The middle value (the mean of the two middle ones for an even count); 0 for none.
double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

using SectionsOfRun =
    std::function<std::vector<RouteSection>(int k, const std::vector<PeriodState>&)>;

StudyMethodResult RunMethod(const ScenarioConfig& config, const StudyParams& params, int index,
                            const SectionsOfRun& sections_of_run) {
  const MethodSpec& spec = kMethods[index];
  const FilterKind filter = FilterOf(index, params);
  ActiveMonteCarloParams mc;
  mc.mc.runs = params.runs;
  mc.mc.seed = params.seed;
  mc.mc.threads = params.threads;
  mc.mc.keep_runs = false;  // run 0 and the summaries are enough; memory stays one batch
  if (params.progress) {
    mc.mc.progress = [&params, index](int done, int total) { params.progress(index, done, total); };
  }
  mc.keep_period_states = index == kSwslam;  // the route runs are measured on its sections
  mc.sections_of_run = sections_of_run;
  if (params.progress) params.progress(index, 0, params.runs);
  const auto start = std::chrono::steady_clock::now();
  ActiveMonteCarloResult r = RunActiveMonteCarlo(
      config, FactoryForFilter(filter, params.particles, config), spec.planner, mc);
  StudyMethodResult m;
  m.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.key = spec.key;
  m.title = StudyMethodTitle(index, params);
  m.filter = filter;
  m.planner = spec.planner;
  std::vector<double> position, heading, anees;
  for (const RunSummary& s : r.mc.summaries) {
    position.push_back(s.rmse.position_m);
    heading.push_back(s.rmse.heading_rad);
    anees.push_back(s.anees);
  }
  m.position_rms_m = SpreadOf(position);
  m.heading_rms_rad = SpreadOf(heading);
  m.anees_run_median = Median(anees);
  m.mc = std::move(r.mc);
  m.traces = std::move(r.traces);
  m.sections = std::move(r.sections);
  return m;
}

}  // namespace

StudyResult RunStudy(const ScenarioConfig& config, const StudyParams& params) {
  if (params.runs < 1) throw InputError("study: runs must be at least 1");
  if (params.particles < 1) throw InputError("study: particles must be at least 1");
  if (params.fastslam == FilterKind::kEkf) {
    throw InputError("study: the route's particle filter must be fastslam1 or fastslam2");
  }
  StudyResult result;
  result.params = params;
  result.methods.resize(std::size(kMethods));
  result.methods[kSwslam] = RunMethod(config, params, kSwslam, nullptr);
  std::vector<ActiveRunTrace>& swslam = result.methods[kSwslam].traces;
  const SectionsOfRun carried = [&swslam](int k, const std::vector<PeriodState>& periods) {
    const ActiveRunTrace& source = swslam[static_cast<std::size_t>(k)];
    std::vector<RouteSection> sections;
    for (const SectionStats& s : source.sections) sections.push_back(s.section);
    return CarrySections(sections, source.period_states, periods);
  };
  for (int i = 0; i < kSwslam; ++i) result.methods[i] = RunMethod(config, params, i, carried);
  for (ActiveRunTrace& trace : swslam) std::vector<PeriodState>().swap(trace.period_states);
  return result;
}

std::string StudyMethodTitle(int index, const StudyParams& params) {
  if (index < 0 || index >= static_cast<int>(std::size(kMethods))) {
    throw std::invalid_argument("StudyMethodTitle: no method " + std::to_string(index));
  }
  return index == kSwslam ? "SWSLAM" : std::string(FilterTitle(FilterOf(index, params)));
}

std::string_view StudySectionsNote() {
  return "Section i is the i-th area of interest SWSLAM detected in a run, from the detecting "
         "observation period until the route waypoint the vehicle was heading for is reached "
         "(after the detour). Route run k (EKF-SLAM, FastSLAM) is measured on the sections of "
         "SWSLAM's run k carried onto the route: from the period of the same route leg nearest "
         "to where SWSLAM detected the area, until that waypoint is reached. Figures are means "
         "over the runs that have the section. A step of the seed's tables is an observation "
         "period; observations are counted from the simulator's truth.";
}

const std::array<PaperMethodFigures, 3>& Seed001Figures() {
  // Seed 001, Tables 1-3 (sections 1-3), Table 4 (position) and Table 5 (direction angle).
  static const std::array<PaperMethodFigures, 3> figures = {{
      {"ekf_slam",
       {{{564, 19, 14}, {1018, 18, 30}, {758, 14, 18}}},
       {0.3539, 0.2537},
       {0.0081, 0.0054}},
      {"fastslam",
       {{{564, 19, 14}, {1018, 18, 30}, {758, 14, 18}}},
       {0.5611, 0.2733},
       {0.0077, 0.0052}},
      {"swslam",
       {{{1056, 26, 23}, {1765, 33, 46}, {1365, 19, 28}}},
       {0.2019, 0.2286},
       {0.0061, 0.0052}},
  }};
  return figures;
}

const PaperMethodFigures& Seed001FiguresOf(std::string_view key) {
  for (const PaperMethodFigures& p : Seed001Figures()) {
    if (p.key == key) return p;
  }
  throw std::invalid_argument("no paper figures for method " + std::string(key));
}

}  // namespace slamkit
