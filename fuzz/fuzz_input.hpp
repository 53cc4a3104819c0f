#pragma once

// Shared by the harnesses: the readers take paths, so each fuzz input is written to a file in a
// directory of this process's own (several harnesses, or libFuzzer's -jobs, may run at once).

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

namespace slamkit::fuzz {

// The process's scratch directory, made on first use and removed at exit (left behind when the
// process dies of a finding). /dev/shm when there is one: the harnesses write a file per input,
// and a RAM disk keeps that off the real disk.
inline const std::filesystem::path& ScratchDir() {
  // Never destroyed: a static path object would be destroyed before the atexit handler, which
  // is registered while the object is still being made, runs and reads it.
  static const std::filesystem::path* const dir = [] {
    std::error_code ec;
    const std::string root = std::filesystem::is_directory("/dev/shm", ec) ? "/dev/shm" : "/tmp";
    std::string pattern = root + "/slamkit_fuzz_XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("slamkit fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(ScratchDir(), ignored);
    });
    return new std::filesystem::path(pattern);
  }();
  return *dir;
}

// Writes `bytes` to ScratchDir() / name, replacing the previous input's file; aborts when it
// cannot (a harness problem, not a finding in the reader).
inline std::filesystem::path WriteFile(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = ScratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "slamkit fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Stops the run with a message when a reader broke a promise of its header: libFuzzer reports
// the abort as a crash and saves the input.
inline void Check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "slamkit fuzz: broken postcondition: %s\n", what);
    std::abort();
  }
}

}  // namespace slamkit::fuzz
