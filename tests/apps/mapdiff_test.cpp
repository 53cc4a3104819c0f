// `slamkit mapdiff` end to end: two map_server maps written here, compared by the command.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

// A w × h map at 0.1 m, free but for an occupied bottom row of `wall` cells, as map.yaml and
// map.pgm in `dir`; `origin_x` moves it.
fs::path WriteMap(const fs::path& dir, int w, int h, int wall, double origin_x = 0.0,
                  double resolution = 0.1) {
  fs::create_directories(dir);
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w * h), 254);
  for (int x = 0; x < wall; ++x) pixels[static_cast<std::size_t>((h - 1) * w + x)] = 0;
  std::ofstream pgm(dir / "map.pgm", std::ios::binary);
  pgm << "P5\n" << w << " " << h << "\n255\n";
  pgm.write(reinterpret_cast<const char*>(pixels.data()),
            static_cast<std::streamsize>(pixels.size()));
  std::ofstream(dir / "map.yaml") << "image: map.pgm\nresolution: " << resolution << "\norigin: ["
                                  << origin_x << ", 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
                                  << "free_thresh: 0.196\n";
  return dir / "map.yaml";
}

TEST(MapDiff, AMapAgainstItselfAndAgainstOneWithAShorterWall) {
  const fs::path dir = FreshDir("mapdiff");
  const fs::path a = WriteMap(dir / "a", 20, 10, 10), b = WriteMap(dir / "b", 20, 10, 5);
  const CliResult same = RunShell("mapdiff " + a.string() + " " + a.string() + " --json");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  const nlohmann::json s = nlohmann::json::parse(same.output);
  EXPECT_EQ(s["kl_divergence"], 0.0);
  EXPECT_EQ(s["dice_occupied"], 1.0);
  EXPECT_EQ(s["cells"], 200);
  const CliResult other = RunShell("mapdiff " + a.string() + " " + b.string() + " --json");
  ASSERT_EQ(other.exit_code, 0) << other.output;
  const nlohmann::json o = nlohmann::json::parse(other.output);
  EXPECT_GT(o["kl_divergence"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(o["dice_occupied"].get<double>(), 2.0 * 5.0 / 15.0);
  EXPECT_DOUBLE_EQ(o["cell_accuracy"].get<double>(), 195.0 / 200.0);
  const CliResult text = RunCli("mapdiff " + a.string() + " " + b.string());
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.output.find("KL divergence"), std::string::npos) << text.output;
}

// A wall one cell up in the second map: Ψ 0 as is, 1 with --tolerance 1, and with --align the
// second is moved back down by the cell (its shift in the JSON).
TEST(MapDiff, ToleranceAndAlignment) {
  const fs::path dir = FreshDir("mapdiff_align");
  const fs::path a = WriteMap(dir / "a", 20, 10, 12), b = WriteMap(dir / "b", 20, 10, 12);
  {  // b's wall one row up: swap its last two rows
    std::ofstream(dir / "b" / "map.yaml") << "image: map.pgm\nresolution: 0.1\norigin: [0.0, "
                                          << "0.1, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
                                          << "free_thresh: 0.196\n";
  }
  const std::string maps = a.string() + " " + b.string() + " --json";
  const auto exact = nlohmann::json::parse(RunShell("mapdiff " + maps).output);
  EXPECT_EQ(exact["dice_occupied"], 0.0);
  const auto tolerant =
      nlohmann::json::parse(RunShell("mapdiff " + maps + " --tolerance 1").output);
  EXPECT_EQ(tolerant["dice_occupied"], 1.0);
  const CliResult aligned = RunShell("mapdiff " + maps + " --align --align-shift 0.5");
  ASSERT_EQ(aligned.exit_code, 0) << aligned.output;
  const auto j = nlohmann::json::parse(aligned.output);
  EXPECT_NEAR(j["alignment"]["y_m"].get<double>(), -0.1, 1e-9);
  EXPECT_EQ(j["dice_occupied"], 1.0);
}

TEST(MapDiff, MapsThatCannotBeComparedAreInputErrors) {
  const fs::path dir = FreshDir("mapdiff_errors");
  const fs::path a = WriteMap(dir / "a", 10, 10, 3);
  const fs::path half = WriteMap(dir / "half", 10, 10, 3, 0.05);
  const fs::path fine = WriteMap(dir / "fine", 10, 10, 3, 0.0, 0.05);
  for (const fs::path& b : {half, fine}) {
    const CliResult r = RunCli("mapdiff " + a.string() + " " + b.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(b.string()), std::string::npos) << r.output;
  }
  const CliResult missing = RunCli("mapdiff " + a.string() + " " + (dir / "none.yaml").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("none.yaml"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace slamkit::testing
