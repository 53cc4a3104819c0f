#pragma once

#include <CLI/CLI.hpp>

namespace slamkit::app {

// Each Register* adds one subcommand to `app`; its callback runs the command and stores the
// exit code in `exit_code`.
void RegisterMonteCarlo(CLI::App& app, int& exit_code);
void RegisterDemo(CLI::App& app, int& exit_code);
void RegisterRun(CLI::App& app, int& exit_code);
void RegisterGrid(CLI::App& app, int& exit_code);
void RegisterGridSim(CLI::App& app, int& exit_code);
void RegisterGridExplore(CLI::App& app, int& exit_code);
void RegisterSuite(CLI::App& app, int& exit_code);
void RegisterExplore(CLI::App& app, int& exit_code);
void RegisterFeatures(CLI::App& app, int& exit_code);
void RegisterStudy(CLI::App& app, int& exit_code);
void RegisterCoop(CLI::App& app, int& exit_code);
void RegisterMapDiff(CLI::App& app, int& exit_code);
void RegisterPoseGraph(CLI::App& app, int& exit_code);
void RegisterLocalize(CLI::App& app, int& exit_code);
void RegisterMerge(CLI::App& app, int& exit_code);
void RegisterReport(CLI::App& app, int& exit_code);

}  // namespace slamkit::app
