// libFuzzer's entry points for every reader's harness (harnesses.hpp): the harness is chosen
// once, at start-up, by the program's name, so `bin/carmen_fuzzer` fuzzes the CARMEN reader
// with libFuzzer's own command line unchanged.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "harnesses.hpp"

namespace {

const slamkit::fuzz::Harness* g_harness = nullptr;

std::string ReaderOf(const char* program) {
  std::string name = program;
  name = name.substr(name.find_last_of('/') + 1);  // npos + 1 == 0: no folder
  const std::string suffix = "_fuzzer";
  if (name.size() > suffix.size() && name.ends_with(suffix)) {
    name.resize(name.size() - suffix.size());
  }
  return name;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  const std::string reader = *argc > 0 ? ReaderOf((*argv)[0]) : "";
  for (const slamkit::fuzz::Harness& h : slamkit::fuzz::kHarnesses) {
    if (reader == h.reader) g_harness = &h;
  }
  if (g_harness == nullptr) {
    std::fprintf(stderr, "slamkit fuzz: no harness for '%s'; start this program as READER_fuzzer "
                         "(the links beside it), READER one of:", reader.c_str());
    for (const slamkit::fuzz::Harness& h : slamkit::fuzz::kHarnesses) {
      std::fprintf(stderr, " %s", h.reader);
    }
    std::fprintf(stderr, "\n");
    std::exit(2);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return g_harness->run(data, size);
}
