#include "slamkit/runners/landmark/study_outputs.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/landmark/active_outputs.hpp"
#include "slamkit/runners/landmark/outputs.hpp"

namespace slamkit {
namespace {

constexpr int kPaperSections = 3;  // seed 001 Tables 1-3

const SectionMean* SectionAt(const StudyMethodResult& m, int i) {
  return i < static_cast<int>(m.sections.size()) ? &m.sections[static_cast<std::size_t>(i)]
                                                 : nullptr;
}

void WriteSectionTableCsv(const std::filesystem::path& path, const StudyResult& result, int i) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "method,runs,observations,observations_per_period,observations_per_landmark,periods,"
           "landmarks,paper_observations,paper_observations_per_period,"
           "paper_observations_per_landmark\n";
    for (const StudyMethodResult& m : result.methods) {
      const PaperSectionRow& p = Seed001FiguresOf(m.key).sections[static_cast<std::size_t>(i)];
      const SectionMean* s = SectionAt(m, i);
      out << (s ? fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", m.key, s->runs,
                              s->observations, s->observations_per_period,
                              s->observations_per_landmark, s->periods, s->landmarks)
                : fmt::format("{},0,,,,,", m.key))
          << fmt::format(",{},{},{}\n", p.observations, p.observations_per_period,
                         p.observations_per_landmark);
    }
  });
}

void WriteErrorTableCsv(const std::filesystem::path& path, const StudyResult& result,
                        bool position) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << (position ? "method,runs,mean_m,variance_m2" : "method,runs,mean_rad,variance_rad2")
        << ",paper_mean,paper_variance\n";
    for (const StudyMethodResult& m : result.methods) {
      const Spread& ours = position ? m.position_rms_m : m.heading_rms_rad;
      const PaperMethodFigures& p = Seed001FiguresOf(m.key);
      const MeanVariance& paper = position ? p.position_m : p.heading_rad;
      out << fmt::format("{},{},{:.17g},{:.17g},{},{}\n", m.key, m.mc.run_count, ours.mean,
                         ours.variance, paper.mean, paper.variance);
    }
  });
}

void WriteSectionsCsv(const std::filesystem::path& path, const StudyResult& result) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "method,section,runs,periods,observations,landmarks,observations_per_period,"
           "observations_per_landmark\n";
    for (const StudyMethodResult& m : result.methods) {
      for (const SectionMean& s : m.sections) {
        out << fmt::format("{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", m.key, s.index + 1,
                           s.runs, s.periods, s.observations, s.landmarks,
                           s.observations_per_period, s.observations_per_landmark);
      }
    }
  });
}

// One row per step of the longest method; a method whose runs all ended leaves its cells empty.
void WriteNeesCsv(const std::filesystem::path& path, const StudyResult& result) {
  const MonteCarloResult* longest = &result.methods.front().mc;
  for (const StudyMethodResult& m : result.methods) {
    if (m.mc.t_s.size() > longest->t_s.size()) longest = &m.mc;
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "t_s";
    for (const StudyMethodResult& m : result.methods)
      out << "," << m.key << "_anees," << m.key << "_runs";
    out << "\n";
    for (std::size_t k = 0; k < longest->t_s.size(); ++k) {
      out << fmt::format("{:.6f}", longest->t_s[k]);
      for (const StudyMethodResult& m : result.methods) {
        out << (k < m.mc.anees.size()
                    ? fmt::format(",{:.17g},{}", m.mc.anees[k], m.mc.runs_at_step[k])
                    : std::string(",,"));
      }
      out << "\n";
    }
  });
}

nlohmann::json MethodJson(const StudyMethodResult& m) {
  const MonteCarloResult& mc = m.mc;
  const PaperMethodFigures& paper = Seed001FiguresOf(m.key);
  nlohmann::json paper_sections = nlohmann::json::array();
  for (const PaperSectionRow& s : paper.sections) {
    paper_sections.push_back({{"observations", s.observations},
                              {"observations_per_period", s.observations_per_period},
                              {"observations_per_landmark", s.observations_per_landmark}});
  }
  nlohmann::json per_run = nlohmann::json::array();
  for (std::size_t k = 0; k < mc.summaries.size(); ++k) {
    nlohmann::json entry = RunSummaryJson(static_cast<int>(k), mc.summaries[k]);
    if (k < m.traces.size()) entry.update(ActiveRunTraceJson(m.traces[k]));
    per_run.push_back(entry);
  }
  nlohmann::json j = MonteCarloResultJson(mc);
  j.update({{"key", m.key},
            {"title", m.title},
            {"filter", std::string(FilterName(m.filter))},
            {"planner", std::string(PlannerName(m.planner))},
            {"wall_time_s", m.wall_time_s},
            {"anees_run_median", m.anees_run_median},
            {"position_rms_m",
             {{"mean", m.position_rms_m.mean}, {"variance", m.position_rms_m.variance}}},
            {"heading_rms_rad",
             {{"mean", m.heading_rms_rad.mean}, {"variance", m.heading_rms_rad.variance}}},
            {"sections", SectionMeansJson(m.sections)},
            {"paper",
             {{"sections", paper_sections},
              {"position_rms",
               {{"mean", paper.position_m.mean}, {"variance", paper.position_m.variance}}},
              {"heading_rms_rad",
               {{"mean", paper.heading_rad.mean}, {"variance", paper.heading_rad.variance}}}}},
            {"per_run", per_run}});
  return j;
}

}  // namespace

nlohmann::json StudyJson(const ScenarioConfig& config, const StudyResult& result) {
  nlohmann::json methods = nlohmann::json::array();
  for (const StudyMethodResult& m : result.methods) methods.push_back(MethodJson(m));
  return {{"scenario", config.scenario.name},
          {"known_association", config.ekf.known_association()},
          {"runs", result.params.runs},
          {"seed", result.params.seed},
          {"particles", result.params.particles},
          {"sections_note", std::string(StudySectionsNote())},
          {"methods", methods},
          {"params", ScenarioParamsJson(config)}};
}

void WriteStudyOutputs(const std::filesystem::path& dir, const ScenarioConfig& config,
                       const StudyResult& result) {
  std::filesystem::create_directories(dir);
  for (int i = 0; i < kPaperSections; ++i) {
    WriteSectionTableCsv(dir / fmt::format("table{}.csv", i + 1), result, i);
  }
  WriteErrorTableCsv(dir / "table4.csv", result, true);
  WriteErrorTableCsv(dir / "table5.csv", result, false);
  WriteSectionsCsv(dir / "sections.csv", result);
  WriteNeesCsv(dir / "nees.csv", result);
  WriteFileAtomically(dir / "tables.md", StudyTablesMarkdown(result));
  nlohmann::json study = StudyJson(config, result);
  WriteJson(dir / "study.json", study);
  for (nlohmann::json& method : study["methods"]) method.erase("per_run");
  WriteJson(dir / "metrics.json", study);
}

}  // namespace slamkit
