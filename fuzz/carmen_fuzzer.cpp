// ReadCarmenLog on a plain-text log (the input as the file's bytes).

#include <cstddef>
#include <cstdint>

#include "carmen_common.hpp"
#include "harnesses.hpp"

int slamkit::fuzz::FuzzCarmen(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  ReadBothWays(WriteFile("log.clf", AsText(data, size)));
  return 0;
}
