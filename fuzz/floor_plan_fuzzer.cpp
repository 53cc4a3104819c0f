// ReadFloorPlanFile (`x1 y1 x2 y2` and `poly ...` lines).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/floor_plan_reader.hpp"

int slamkit::fuzz::FuzzFloorPlan(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const slamkit::Walls walls =
        slamkit::ReadFloorPlanFile(WriteFile("plan.txt", AsText(data, size)));
    Check(!walls.empty(), "a floor plan has at least one wall");
    for (const auto& [a, b] : walls) {
      Check(a.allFinite() && b.allFinite() && a != b, "walls are finite, of non-zero length");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
