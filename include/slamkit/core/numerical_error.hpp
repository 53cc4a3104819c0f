#pragma once

#include <stdexcept>

namespace slamkit {

// A filter's state went bad: a non-finite entry, an asymmetric or indefinite covariance, weights
// that no longer normalise. Thrown by the state-health checks (state_health.hpp) so that NaN
// never reaches an output silently. The message names the filter, the step and the check that
// failed, e.g. "EkfSlam after update 17: covariance entry (4, 2) is nan".
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace slamkit
