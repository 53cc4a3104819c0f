#pragma once

#include <gtest/gtest.h>

#include <string>

#include "slamkit/io/error.hpp"

namespace slamkit::testing {

// The message of the InputError that `read()` throws; a test failure (and "") when it throws none.
template <typename Read>
std::string InputErrorOf(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError was thrown";
  return "";
}

}  // namespace slamkit::testing
