// `slamkit mapdiff A.yaml B.yaml`: two map_server maps compared cell by cell (SPEC S4).
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/commands.hpp"
#include "common/options.hpp"
#include "slamkit/eval/map_alignment.hpp"
#include "slamkit/eval/map_comparison.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/map_reader.hpp"

namespace slamkit::app {
namespace {

struct MapDiffOptions {
  std::string first;
  std::string second;
  bool json = false;
  bool align = false;
  MapComparisonParams params;
  MapAlignmentParams alignment;
};

int RunMapDiff(const MapDiffOptions& o) {
  const OccupancyImage a = ReadOccupancyImage(o.first);
  OccupancyImage b = ReadOccupancyImage(o.second);
  MapComparison c;
  std::optional<MapAlignment> aligned;
  try {
    if (o.align) {
      aligned = AlignMaps(a, b, o.alignment);
      b = ResampleMap(a, b, aligned->transform);
    }
    c = CompareMaps(a, b, o.params);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("{} and {}: {}", o.first, o.second, e.what()));
  }
  if (o.json) {
    const nlohmann::json j = {{"first", o.first},
                              {"second", o.second},
                              {"cells", c.cells},
                              {"known_cells", c.known_cells},
                              {"kl_divergence", c.kl_divergence},
                              {"cell_accuracy", c.cell_accuracy},
                              {"dice_occupied", c.dice_occupied}};
    nlohmann::json out = j;
    if (aligned) {
      out["alignment"] = {{"x_m", aligned->transform.x()},
                          {"y_m", aligned->transform.y()},
                          {"theta_rad", aligned->transform.theta()},
                          {"score", aligned->score}};
    }
    fmt::print("{}\n", out.dump(2));
    return 0;
  }
  if (aligned) {
    fmt::print("second map aligned onto the first by x {:.3f} m, y {:.3f} m, theta {:.4f} rad "
               "(wall score {:.3f})\n", aligned->transform.x(), aligned->transform.y(),
               aligned->transform.theta(), aligned->score);
  }
  fmt::print("cells in the overlap: {} ({} known in either map)\n", c.cells, c.known_cells);
  fmt::print("KL divergence (Eq. 24, first against second): {:.6g}\n", c.kl_divergence);
  fmt::print("cell accuracy (same class, over the known cells): {:.6f}\n", c.cell_accuracy);
  fmt::print("Dice of the occupied cells (Psi, Eq. 5): {:.6f}\n", c.dice_occupied);
  return 0;
}

}  // namespace

void RegisterMapDiff(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MapDiffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mapdiff",
      "two occupancy maps (map_server YAML + PGM, one resolution) compared over their overlap: "
      "the KL divergence of SPEC S4's Eq. 24, cell accuracy and the occupied cells' Dice "
      "similarity (Eq. 5). A pixel v is the occupancy p = (255 - v) / 255; p above "
      "--occupied-thresh is occupied, below --free-thresh free, else unknown. Cells unknown in "
      "both maps are left out; an unknown cell against a known one counts as p = 0.5; p is "
      "clamped to [floor, 1 - floor] so that 0 and 1 stay finite");
  AddExamples(cmd, {
               "out/intel/map.yaml out/intel_graph/map.yaml --json   # after both grid examples"});
  cmd->add_option("first", o->first, "the first map's YAML (P in Eq. 24)")->required();
  cmd->add_option("second", o->second, "the second map's YAML (Q)")->required();
  cmd->add_flag("--json", o->json, "print the figures as JSON");
  cmd->add_option("--occupied-thresh", o->params.occupied_threshold,
                  "occupancy above which a cell is occupied")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--free-thresh", o->params.free_threshold,
                  "occupancy below which a cell is free")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--floor", o->params.probability_floor,
                  "KL: occupancies clamped to [floor, 1 - floor]")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 0.499));
  cmd->add_flag("--align", o->align,
                "first lay the second map's walls onto the first's (a rigid motion within "
                "--align-shift and --align-turn), then compare the second resampled into the "
                "first's cells");
  cmd->add_option("--align-shift", o->alignment.max_shift_m, "--align: largest shift searched [m]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--align-turn", o->alignment.max_rotation_rad,
                  "--align: largest turn searched [rad]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3.1416));
  cmd->add_option("--tolerance", o->params.dice_tolerance_cells,
                  "Psi: an occupied cell matches one of the other map within N cells (0: Eq. 5)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  cmd->callback([o, &exit_code] { exit_code = RunMapDiff(*o); });
}

}  // namespace slamkit::app
