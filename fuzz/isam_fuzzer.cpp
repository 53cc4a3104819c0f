// ReadIsamLog (ODOMETRY and LANDMARK lines).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/isam_reader.hpp"

int slamkit::fuzz::FuzzIsam(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const slamkit::IsamLog log = slamkit::ReadIsamLog(WriteFile("log.isam", AsText(data, size)));
    for (const slamkit::IsamStep& step : log.steps) {
      Check(step.odometry.allFinite() && step.odometry_covariance.allFinite(),
            "odometry values are finite");
      for (const auto& sighting : step.sightings) Check(sighting.id >= 0, "landmark ids >= 0");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
