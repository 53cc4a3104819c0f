// ReadRelations (`t1 t2 x y z roll pitch yaw` lines, plain or gzip).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/relations_reader.hpp"

int slamkit::fuzz::FuzzRelations(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const auto relations = slamkit::ReadRelations(WriteFile("log.relations", AsText(data, size)));
    Check(!relations.empty(), "a relations file has at least one relation");
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
