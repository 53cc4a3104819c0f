#pragma once

#include <filesystem>

#include "slamkit/runners/cooperative/coop_study.hpp"

namespace slamkit::app {

// DIR/paths.png (the true and estimated paths of run 0 of the last mode) and DIR/covariance.png
// (each mode's ‖C_pp‖ over time per vehicle, the mean over the runs).
void WriteCoopFigures(const std::filesystem::path& dir, const CoopStudyResult& result);

}  // namespace slamkit::app
