#pragma once

#include <memory>
#include <string>

#include "slamkit/filters/selection/selection.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"

namespace slamkit {

// The selection policies a config or a command line can name: the three correction stages of
// SPEC S1 (and the O(1) form of the second). Any other SelectionPolicy can be passed to a filter.
enum class SelectionKind { kAll, kEntropy, kEntropyFast, kCovariance };

// "all", "entropy", "entropy-fast", "covariance"; and back. Throws std::invalid_argument on
// another name, listing the valid ones.
SelectionKind SelectionKindOf(const std::string& name);
std::string SelectionKindName(SelectionKind kind);

// The policy `kind` names, with its params.
std::unique_ptr<SelectionPolicy> MakeSelectionPolicy(SelectionKind kind,
                                                     const CovarianceSelectionParams& covariance,
                                                     const EntropySelectionParams& entropy);

// The correction's counted floating-point work in an n-state filter: 2n² per applied update
// (the covariance downdate), plus, for the dense entropy policy, the two n×n Cholesky
// factorisations (2n³/3) per candidate that its log-determinants take.
double CorrectionFlops(SelectionKind kind, const SelectionStats& stats, int state_size);

}  // namespace slamkit
