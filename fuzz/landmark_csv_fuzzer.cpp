// ReadLandmarkCsv (`id,x_m,y_m` lines).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/landmark_csv.hpp"

int slamkit::fuzz::FuzzLandmarkCsv(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const slamkit::LandmarkWorld world =
        slamkit::ReadLandmarkCsv(WriteFile("landmarks.csv", AsText(data, size)));
    Check(!world.landmarks.empty(), "a landmark file has at least one landmark");
    for (const slamkit::Landmark& l : world.landmarks) {
      Check(l.id >= 0 && l.position_m.allFinite(), "ids are non-negative, positions finite");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
