#include "slamkit/runners/landmark/active_outputs.hpp"

#include <string>

#include <fmt/format.h>

#include "slamkit/runners/landmark/outputs.hpp"

namespace slamkit {
namespace {

nlohmann::json PointJson(const Eigen::Vector2d& p) {
  return {p.x(), p.y()};
}

}  // namespace

nlohmann::json SectionStatsJson(const SectionStats& s) {
  return {{"first_period", s.section.first_period},
          {"end_period", s.section.end_period},
          {"route_waypoint", s.section.route_waypoint},
          {"detour_m", s.section.detour_m ? PointJson(*s.section.detour_m) : nlohmann::json()},
          {"detour_reached", s.section.detour_reached},
          {"periods", s.periods},
          {"observations", s.observations},
          {"landmarks", s.landmarks},
          {"observations_per_period", s.observations_per_period},
          {"observations_per_landmark", s.observations_per_landmark}};
}

nlohmann::json SectionMeansJson(const std::vector<SectionMean>& sections) {
  nlohmann::json out = nlohmann::json::array();
  for (const SectionMean& m : sections) {
    out.push_back({{"section", m.index + 1},
                   {"runs", m.runs},
                   {"periods", m.periods},
                   {"observations", m.observations},
                   {"landmarks", m.landmarks},
                   {"observations_per_period", m.observations_per_period},
                   {"observations_per_landmark", m.observations_per_landmark}});
  }
  return out;
}

std::string SectionMeansText(const std::vector<SectionMean>& sections) {
  std::string text;
  for (const SectionMean& s : sections) {
    text += fmt::format(
        "  section {} ({} runs): {:.1f} observations, {:.1f} per period, {:.1f} per landmark\n",
        s.index + 1, s.runs, s.observations, s.observations_per_period,
        s.observations_per_landmark);
  }
  return text;
}

nlohmann::json ActiveRunTraceJson(const ActiveRunTrace& trace) {
  nlohmann::json sections = nlohmann::json::array();
  for (const SectionStats& s : trace.sections) sections.push_back(SectionStatsJson(s));
  nlohmann::json detours = nlohmann::json::array();
  for (const Eigen::Vector2d& c : trace.centres_m) detours.push_back(PointJson(c));
  return {{"steps", trace.steps},
          {"periods", trace.periods},
          {"sections", sections},
          {"detours", detours}};
}

nlohmann::json ActiveMonteCarloMetrics(const ScenarioConfig& config, const MonteCarloParams& params,
                                       const ActiveMonteCarloResult& result, FilterKind filter,
                                       int particles) {
  nlohmann::json metrics = MonteCarloMetrics(config, params, result.mc);
  metrics["filter"] = std::string(FilterName(filter));
  if (filter != FilterKind::kEkf) metrics["particles"] = particles;
  metrics["planner"] = std::string(PlannerName(result.planner));
  metrics["sections"] = SectionMeansJson(result.sections);
  return metrics;
}

}  // namespace slamkit
