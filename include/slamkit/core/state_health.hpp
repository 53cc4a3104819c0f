#pragma once

#include <Eigen/Core>
#include <string_view>

#include "slamkit/core/numerical_error.hpp"

namespace slamkit {

// When a filter checks the health of its state (finite, symmetric, positive semi-definite).
enum class StateHealthMode {
  kOff,
  // Only when asked (CheckOutputHealth()), which runners do before writing results.
  kAtOutput,
  // Also at the end of every update (and, on the pose alone, of every prediction).
  kEveryUpdate,
};

// Every update in Debug and sanitizer builds, where catching the first bad step matters more
// than speed; at output only in Release, where outputs must stay as fast (and bit-identical) as
// without the checks. Tests force kEveryUpdate where they rely on it.
#ifdef NDEBUG
inline constexpr StateHealthMode kDefaultStateHealthMode = StateHealthMode::kAtOutput;
#else
inline constexpr StateHealthMode kDefaultStateHealthMode = StateHealthMode::kEveryUpdate;
#endif

struct StateHealthParams {
  StateHealthMode mode = kDefaultStateHealthMode;
  // |P_ij − P_ji| allowed, relative to the largest diagonal entry: rounding in a product such as
  // U Uᵀ leaves differences of order 1e-16 of the scale.
  double symmetry_tolerance = 1e-9;
  // The smallest eigenvalue allowed is −psd_tolerance · max_i P_ii: singular directions (a pose
  // with zero initial covariance, landmarks converged to full correlation) sit at zero and
  // rounding puts them a few 1e-16 of the scale on either side.
  double psd_tolerance = 1e-9;
  // Finiteness and symmetry cost O(n²), an update's own order, and run at every update; the PSD
  // test is a Cholesky factorisation, O(n³), and runs every max(1, ⌊psd_interval_per_entry · n⌋)
  // -th update, so that its cost per update also stays O(n²) (with 1/16: every update up to
  // n = 31, i.e. 14 landmarks; every 12th at 100 landmarks). At output all three run.
  double psd_interval_per_entry = 1.0 / 16.0;

  bool every_update() const { return mode == StateHealthMode::kEveryUpdate; }
  bool enabled() const { return mode != StateHealthMode::kOff; }
  // Whether the PSD test is due at every-update check number `update` (1, 2, …) of a state of
  // `state_size` entries.
  bool PsdDue(long update, int state_size) const;
};

// Throws NumericalError "`where`: `what` entry (i, j) is nan" (or inf) at the first non-finite
// entry of `m`, in column-major order.
void CheckFinite(const Eigen::Ref<const Eigen::MatrixXd>& m, std::string_view what,
                 std::string_view where);

// The health of a Gaussian state: a finite mean, a finite and symmetric covariance (within
// params.symmetry_tolerance) and, if `check_psd`, a positive semi-definite one (smallest
// eigenvalue ≥ −params.psd_tolerance · max_i P_ii). Throws NumericalError naming `where` and the
// check that failed, with the entry or the smallest eigenvalue. Only reads its arguments.
void CheckGaussianHealth(const Eigen::Ref<const Eigen::VectorXd>& mean,
                         const Eigen::Ref<const Eigen::MatrixXd>& covariance,
                         const StateHealthParams& params, bool check_psd, std::string_view where);

}  // namespace slamkit
