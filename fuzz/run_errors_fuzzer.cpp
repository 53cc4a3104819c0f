// ReadRunErrorsCsv (a Monte Carlo run's errors.csv, which `slamkit merge` reads).

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/run_errors_reader.hpp"

int slamkit::fuzz::FuzzRunErrors(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const slamkit::RunErrorsCsv csv =
        slamkit::ReadRunErrorsCsv(WriteFile("errors.csv", AsText(data, size)));
    Check(csv.t_s.size() == csv.errors.size() && csv.errors.size() == csv.nees.size(),
          "one time, error and NEES per line");
    for (std::size_t i = 0; i < csv.nees.size(); ++i) {
      Check(std::isfinite(csv.t_s[i]) && csv.errors[i].allFinite(), "times and errors finite");
      Check(csv.nees[i] >= 0.0, "NEES non-negative, not NaN");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
