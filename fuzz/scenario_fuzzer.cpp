// LoadScenario (scenario YAML, configs/*.yaml). A small valid landmarks.csv sits next to the
// scenario file, so that `world: {kind: csv, landmarks_csv: landmarks.csv}` reaches the CSV
// reader too (the CSV reader's own harness is landmark_csv_fuzzer.cpp).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/scenario_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  static const bool csv_written = (WriteFile("landmarks.csv", "id,x_m,y_m\n0,1,2\n1,3,-4\n"), true);
  (void)csv_written;
  try {
    const slamkit::ScenarioConfig config =
        slamkit::LoadScenario(WriteFile("scenario.yaml", AsText(data, size)));
    Check(config.scenario.route.waypoints_m.size() >= 2, "a scenario has a route");
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
