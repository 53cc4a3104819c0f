#pragma once

#include <stdexcept>
#include <string>

namespace slamkit {

// Bad input: a file that cannot be read, parsed or validated. The message names the file and the
// line or key, so the command line can print it as is and exit with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace slamkit
