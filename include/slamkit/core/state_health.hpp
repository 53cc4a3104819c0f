#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
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
  // test is a Cholesky factorisation, O(n³), and runs at every max(1, ⌊psd_interval_per_entry · n⌋)
  // -th every-update check, so that its cost per update stays O(n²) too: n³/3 every n/2 checks is
  // (2/3) n², below the 8 n² of a scan of 8 sightings' downdates. With 0.5: every 31st check at
  // 30 landmarks (n = 63), every 101st at 100. Under ASan, `mc` of configs/short.yaml (4 runs,
  // 2.9 s without checks) took about 0.4 s more for the PSD tests alone with 1/16 (every 3rd
  // check); with 0.5, all the every-update checks add about 0.2 s. At output all three run.
  double psd_interval_per_entry = 0.5;

  bool every_update() const { return mode == StateHealthMode::kEveryUpdate; }
  bool enabled() const { return mode != StateHealthMode::kOff; }
  // Whether the PSD test is due at every-update check number `update` (1, 2, …) of a state of
  // `state_size` entries.
  bool PsdDue(long update, int state_size) const;
};

// "`what` entry (i, j) is nan" (or inf; "entry i" for a vector) at the first non-finite entry of
// `m` in column-major order; nullopt if there is none.
std::optional<std::string> NonFiniteProblem(const Eigen::Ref<const Eigen::MatrixXd>& m,
                                            std::string_view what);
// The same as a NumericalError "`where`: …".
void CheckFinite(const Eigen::Ref<const Eigen::MatrixXd>& m, std::string_view what,
                 std::string_view where);

// The health of a Gaussian state: a finite mean, a finite and symmetric covariance (within
// params.symmetry_tolerance) and, if `check_psd`, a positive semi-definite one (smallest
// eigenvalue ≥ −params.psd_tolerance · max_i P_ii). Returns what failed, with the entry or the
// smallest eigenvalue (nullopt: healthy); a caller that checks often builds its step's name only
// then. Only reads its arguments.
std::optional<std::string> GaussianHealthProblem(
    const Eigen::Ref<const Eigen::VectorXd>& mean,
    const Eigen::Ref<const Eigen::MatrixXd>& covariance, const StateHealthParams& params,
    bool check_psd);
// The same as a NumericalError "`where`: …".
void CheckGaussianHealth(const Eigen::Ref<const Eigen::VectorXd>& mean,
                         const Eigen::Ref<const Eigen::MatrixXd>& covariance,
                         const StateHealthParams& params, bool check_psd, std::string_view where);

// Throws NumericalError "`where`: `problem`".
[[noreturn]] void ThrowNumericalError(std::string_view where, std::string_view problem);

}  // namespace slamkit
