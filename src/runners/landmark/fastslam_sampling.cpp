#include "slamkit/runners/landmark/fastslam_sampling.hpp"

namespace slamkit {

void AddDelayedSamplingLines(const std::string& section, bool* delayed_sampling,
                             int* window_max_landmarks, config::ParamTable* table) {
  table->push_back(config::Flag(section, "delayed_sampling", delayed_sampling,
                                "FastSLAM 2.0: sample a pose only once its landmarks settle"));
  table->push_back(config::Integer(section, "window_max_landmarks", window_max_landmarks, 1,
                                   "a delayed-sampling window growing past this is drawn"));
}

}  // namespace slamkit
