#pragma once

// What every command's options share: number checks that say their range in words, seed lists,
// and the options that a params table (config::ParamTable) gives.

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/io/param_table.hpp"

namespace slamkit::app {

// "known", "joint-compatibility" or "nearest-neighbour", for summaries.
const char* AssociationName(AssociationMethod m);

// CLI11 checks for a number > 0 and >= 0 whose message says so ("must be > 0, got 0"), where
// CLI::PositiveNumber's says "not in range 0.000000 to 1797693134862315708...".
CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();
// A seed: digits only, 0 to 2^64 - 1 (CLI11 would read "-1" as 2^64 - 1).
CLI::Validator SeedNumber();

// "K/N" with 1 <= K <= N (ParseShard's message otherwise).
CLI::Validator ShardText();

// "1-5", "1,3,7" or "2" as the list of seeds (`--seeds`); InputError naming --seeds otherwise.
std::vector<std::uint64_t> ParseSeeds(const std::string& text);

// An option for every line of `table` that has a flag, setting the line's target, with its help
// and unit, its default shown and its range checked as the config reader checks it. Returns
// them in the table's order (so that --config can exclude them).
std::vector<CLI::Option*> AddParamOptions(CLI::App* cmd, const config::ParamTable& table);

// Ends `cmd`'s help with `examples`, each the arguments after the command's name, shown after
// the program's name as it was invoked: they run as written from the repository root (the
// datasets in ../shared). tests/apps/help_examples_test.cpp checks each with --dry-run.
void AddExamples(CLI::App* cmd, std::vector<std::string> examples);

}  // namespace slamkit::app
