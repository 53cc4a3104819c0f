#pragma once

// Every reader's harness, one function each (READER_fuzzer.cpp), in one program: libFuzzer
// allows one entry point per program, and one program compiles and links once where thirteen
// programs took 7 % of the sanitizer tree's build (52 of 765 CPU-seconds). fuzz_main.cpp picks
// the harness by the name the program is started under (bin/READER_fuzzer, a link to
// bin/slamkit_fuzzer).

#include <cstddef>
#include <cstdint>

namespace slamkit::fuzz {

int FuzzCarmen(const std::uint8_t* data, std::size_t size);
int FuzzCarmenGz(const std::uint8_t* data, std::size_t size);
int FuzzFloorPlan(const std::uint8_t* data, std::size_t size);
int FuzzIsam(const std::uint8_t* data, std::size_t size);
int FuzzLandmarkCsv(const std::uint8_t* data, std::size_t size);
int FuzzMrclam(const std::uint8_t* data, std::size_t size);
int FuzzOccupancyImage(const std::uint8_t* data, std::size_t size);
int FuzzPoseGraph(const std::uint8_t* data, std::size_t size);
int FuzzRelations(const std::uint8_t* data, std::size_t size);
int FuzzRunErrors(const std::uint8_t* data, std::size_t size);
int FuzzScenario(const std::uint8_t* data, std::size_t size);
int FuzzSuiteManifest(const std::uint8_t* data, std::size_t size);
int FuzzTrajectory(const std::uint8_t* data, std::size_t size);
int FuzzWaypoints(const std::uint8_t* data, std::size_t size);

struct Harness {
  const char* reader;
  int (*run)(const std::uint8_t* data, std::size_t size);
};

inline constexpr Harness kHarnesses[] = {
    {"carmen", &FuzzCarmen},
    {"carmen_gz", &FuzzCarmenGz},
    {"floor_plan", &FuzzFloorPlan},
    {"isam", &FuzzIsam},
    {"landmark_csv", &FuzzLandmarkCsv},
    {"mrclam", &FuzzMrclam},
    {"occupancy_image", &FuzzOccupancyImage},
    {"pose_graph", &FuzzPoseGraph},
    {"relations", &FuzzRelations},
    {"run_errors", &FuzzRunErrors},
    {"scenario", &FuzzScenario},
    {"suite_manifest", &FuzzSuiteManifest},
    {"trajectory", &FuzzTrajectory},
    {"waypoints", &FuzzWaypoints},
};

}  // namespace slamkit::fuzz
