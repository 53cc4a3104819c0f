// ReadWaypoints (`x y` lines, plain or gzip).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/waypoints_reader.hpp"

int slamkit::fuzz::FuzzWaypoints(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const auto waypoints = slamkit::ReadWaypoints(WriteFile("route.txt", AsText(data, size)));
    Check(waypoints.size() >= 2, "a route has at least 2 waypoints");
    for (const auto& w : waypoints) Check(w.allFinite(), "waypoints are finite");
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
