#include "slamkit/filters/selection/selection_kind.hpp"

#include <stdexcept>

namespace slamkit {
namespace {

constexpr const char* kSelectionNames[] = {"all", "entropy", "entropy-fast", "covariance"};

}  // namespace

SelectionKind SelectionKindOf(const std::string& name) {
  for (int k = 0; k < 4; ++k) {
    if (name == kSelectionNames[k]) return static_cast<SelectionKind>(k);
  }
  throw std::invalid_argument("unknown selection policy '" + name +
                              "': expected all, entropy, entropy-fast or covariance");
}

std::string SelectionKindName(SelectionKind kind) {
  return kSelectionNames[static_cast<int>(kind)];
}

double CorrectionFlops(SelectionKind kind, const SelectionStats& stats, int state_size) {
  const double n = state_size;
  double flops = stats.applied * 2.0 * n * n;
  if (kind == SelectionKind::kEntropy) flops += stats.candidates * 2.0 * n * n * n / 3.0;
  return flops;
}

std::unique_ptr<SelectionPolicy> MakeSelectionPolicy(SelectionKind kind,
                                                     const CovarianceSelectionParams& covariance,
                                                     const EntropySelectionParams& entropy) {
  switch (kind) {
    case SelectionKind::kAll: return std::make_unique<SelectAll>();
    case SelectionKind::kEntropy: return std::make_unique<SelectByEntropy>(entropy);
    case SelectionKind::kEntropyFast: return std::make_unique<SelectByEntropyFast>(entropy);
    case SelectionKind::kCovariance: break;
  }
  return std::make_unique<SelectByCovariance>(covariance);
}

}  // namespace slamkit
