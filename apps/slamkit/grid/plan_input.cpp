#include "grid/plan_input.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "slamkit/io/floor_plan_reader.hpp"
#include "slamkit/io/map_reader.hpp"

namespace slamkit::app {
namespace {

// A plan file is a map_server map when its name says YAML, else a walls file: a plan that is
// neither fails on its first line with the walls format's message.
bool IsMapServerMap(const std::filesystem::path& plan) {
  std::string ext = plan.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".yaml" || ext == ".yml";
}

}  // namespace

FloorPlan ReadPlan(const std::string& plan) {
  if (plan == "maze") return MakeSquareMaze();
  if (IsMapServerMap(plan)) return FloorPlanFromOccupancy(ReadOccupancyImage(plan));
  return FloorPlan{ReadFloorPlanFile(plan)};
}

}  // namespace slamkit::app
