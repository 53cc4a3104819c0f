// ReadOccupancyImage (a map_server map: YAML + PGM). The input is `YAML kSeparator PGM`: both
// parts are written to the scratch folder, as map.yaml and map.pgm (the seeds' yaml says
// `image: map.pgm`, so the fuzzer keeps reaching the PGM parser while it mutates the YAML). An
// input without the separator is a PGM under a fixed, valid YAML: the PGM parser on its own.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/map_reader.hpp"

namespace {

constexpr std::string_view kSeparator = "\n===PGM===\n";
constexpr std::string_view kDefaultYaml = "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";

}  // namespace

int slamkit::fuzz::FuzzOccupancyImage(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  const std::string_view input = AsText(data, size);
  const std::size_t split = input.find(kSeparator);
  const std::string_view yaml = split == std::string_view::npos ? kDefaultYaml : input.substr(0, split);
  const std::string_view pgm =
      split == std::string_view::npos ? input : input.substr(split + kSeparator.size());
  // Both files every time: a file left by an earlier input would make runs irreproducible.
  WriteFile("map.pgm", pgm);
  try {
    const slamkit::OccupancyImage image = slamkit::ReadOccupancyImage(WriteFile("map.yaml", yaml));
    Check(image.width >= 1 && image.height >= 1 &&
              image.pixels.size() == static_cast<std::size_t>(image.width) * image.height,
          "the pixels fill width x height");
    Check(image.resolution_m > 0.0 && image.origin_m.allFinite(),
          "positive resolution, finite origin");
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
