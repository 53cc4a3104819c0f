// ReadCarmenLog on a gzip file. The input is the file's raw bytes (seeds are real .gz excerpts),
// so that truncated, garbled, concatenated and wrongly checksummed gzip streams reach zlib and
// LineReader; compressing the input here would only ever produce well-formed streams, whose text
// the plain-text harness (carmen_fuzzer.cpp) already covers.

#include <cstddef>
#include <cstdint>

#include "carmen_common.hpp"
#include "harnesses.hpp"

int slamkit::fuzz::FuzzCarmenGz(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  ReadBothWays(WriteFile("log.gz", AsText(data, size)));
  return 0;
}
