#include "slamkit/runners/grid/grid_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

// configs/grid.yaml documents the defaults: loading it onto other values must give exactly
// GridSlamConfig{}.
TEST(GridConfig, TheShippedFileHoldsEveryDefault) {
  GridSlamConfig config;
  RbpfGridSlamParams& other = config.rbpf;
  other.particles = 7;
  other.motion.srt = 0.9;
  other.odometry_heading_drift_rad_per_m = 0.01;
  other.estimate_heading_drift = true;
  other.heading_drift_prior_m2 = 3.0;
  other.tracking.refinements = 11;
  other.grid.log_odds_hit = 2.0f;
  other.proposal = ProposalScheme::kScanMatch;
  const GridSlamConfig loaded =
      LoadGridConfig(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "grid.yaml", config);
  EXPECT_EQ(GridParamsJson(loaded), GridParamsJson(GridSlamConfig{}));
}

class GridConfigFile : public testing::TempDirTest {};

// The effective parameters in metrics.json, written back as YAML (JSON is YAML), reproduce them.
TEST_F(GridConfigFile, TheParametersJsonLoadsBackToTheSameParameters) {
  GridSlamConfig config;
  RbpfGridSlamParams& p = config.rbpf;
  p.particles = 12;
  p.resampling.scheme = ResamplingScheme::kMultinomial;
  p.tracking_mode = TrackingMode::kTrackOnly;
  p.matcher.coarse_pass = false;
  p.grid.resolution_m = 0.1;
  p.grid.max_cells = 12345;
  p.odometry_heading_drift_rad_per_m = -0.0034;
  p.estimate_heading_drift = true;
  p.heading_drift_prior_m2 = 20.0;
  const fs::path path = WriteFile("params.yaml", GridParamsJson(config).dump(2));
  EXPECT_EQ(GridParamsJson(LoadGridConfig(path)), GridParamsJson(config));
  EXPECT_EQ(GridParamsJson(config)["backend"], "rbpf");
}

TEST_F(GridConfigFile, KeysLeftOutKeepTheDefaults) {
  const RbpfGridSlamParams p =
      LoadGridConfig(WriteFile("g.yaml", "particles: 5\nmotion: {srr: 0.2}\n")).rbpf;
  EXPECT_EQ(p.particles, 5);
  EXPECT_EQ(p.motion.srr, 0.2);
  EXPECT_EQ(p.motion.stt, RbpfGridSlamParams{}.motion.stt);
  EXPECT_EQ(p.tracking.refinements, RbpfGridSlamParams{}.tracking.refinements);
}

TEST_F(GridConfigFile, MistakesNameTheFileLineAndKey) {
  struct Case {
    std::string yaml, part;
  };
  const Case cases[] = {
      {"particles: 0\n", "g.yaml:1: key 'particles'"},
      {"motion:\n  srr: -1\n", "g.yaml:2: key 'motion.srr': must be >= 0"},
      {"motion: {sxx: 1}\n", "sxx"},
      {"motion: {heading_drift_rad_per_m: .inf}\n", "key 'motion.heading_drift_rad_per_m'"},
      {"motion: {heading_drift_prior_m2: 0}\n", "key 'motion.heading_drift_prior_m2': must be > 0"},
      {"proposal: best\n", "key 'proposal': expected one of gaussian, scan_match, got 'best'"},
      {"tracking_mode: on\n", "key 'tracking_mode'"},
      {"resampling: {scheme: random}\n", "key 'resampling.scheme'"},
      {"grid: {resolution_m: 0}\n", "key 'grid.resolution_m': must be > 0"},
      {"grid: {log_odds_min: 5}\n", "key 'grid.log_odds_min': must be below log_odds_max"},
      {"matcher: {beam_stride: fast}\n", "key 'matcher.beam_stride'"},
      {"usable_range: 30\n", "usable_range"},
      {"sampled_start_fraction: 1.5\n", "key 'sampled_start_fraction': must be at most 1"},
      {"heading_sweep_sigmas: -1\n", "key 'heading_sweep_sigmas': must be >= 0"},
      {"graph:\n  matcher: {rescue_sigma_per_m: 3}\n",
       "g.yaml:2: key 'graph.matcher.rescue_sigma_per_m': must be at most 0.2"},
      {"backend: graphs\n", "g.yaml:1: key 'backend': expected one of rbpf, graph, got 'graphs'"}};
  for (const Case& c : cases) {
    const std::string message =
        testing::InputErrorOf([&] { LoadGridConfig(WriteFile("g.yaml", c.yaml)); });
    EXPECT_NE(message.find(c.part), std::string::npos) << c.yaml << "\n" << message;
  }
}

}  // namespace
}  // namespace slamkit
