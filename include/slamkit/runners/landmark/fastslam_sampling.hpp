#pragma once

// FastSLAM's delayed sampling as config lines: one definition of the keys, bounds and help, used
// by every config whose runs may use FastSLAM (iSAM logs, simulated scenarios).

#include <string>

#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/io/param_table.hpp"

namespace slamkit {

// FastSlamParams::delayed_sampling (FastSLAM 2.0 with each particle's own association only) and
// its window's size.
struct FastSlamSampling {
  bool delayed_sampling = false;
  int window_max_landmarks = FastSlamParams{}.window_max_landmarks;
};

// The lines `delayed_sampling` and `window_max_landmarks` under `section`, into the targets.
void AddDelayedSamplingLines(const std::string& section, bool* delayed_sampling,
                             int* window_max_landmarks, config::ParamTable* table);

}  // namespace slamkit
