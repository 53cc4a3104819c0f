#pragma once

#include <array>
#include <span>
#include <vector>

#include "slamkit/filters/block_ekf.hpp"
#include "slamkit/filters/observation_model.hpp"

namespace slamkit {

// The matched observations of one step, offered to a selection policy. S(i), H(i) and R(i) are
// those of observation i linearised at the current posterior: after each Apply() they change, so
// a policy that ranks by them (SPEC S1 item 3, Algorithm 3) re-ranks simply by asking again.
class SelectionSession {
 public:
  virtual ~SelectionSession() = default;

  virtual int size() const = 0;
  virtual BlockMatrix S(int i) const = 0;
  virtual BlockJacobians H(int i) const = 0;
  virtual BlockMatrix R(int i) const = 0;
  virtual bool applied(int i) const = 0;
  // The sequential EKF update with observation i, linearised now; once per observation.
  virtual void Apply(int i) = 0;
};

// Chooses which matched observations update the filter and in what order.
class SelectionPolicy {
 public:
  virtual ~SelectionPolicy() = default;
  virtual void Select(SelectionSession& session) = 0;
};

// Every matched observation, in scan order: the plain sequential EKF.
class SelectAll final : public SelectionPolicy {
 public:
  void Select(SelectionSession& session) override {
    for (int i = 0; i < session.size(); ++i) session.Apply(i);
  }
};

// One matched observation: its model, the blocks it involves and the measurement.
struct MatchedObservation {
  const ObservationModel* model = nullptr;
  std::array<int, kMaxObservedBlocks> blocks{};
  int num_blocks = 0;
  BlockVector z;
  BlockMatrix R;

  std::span<const int> block_view() const { return {blocks.data(), std::size_t(num_blocks)}; }
};

// A SelectionSession on a BlockEkf: linearises on demand, so SelectAll costs nothing beyond the
// updates themselves, and again after every applied update. Updates stay deferred.
class BlockSelectionSession final : public SelectionSession {
 public:
  BlockSelectionSession(BlockEkf& ekf, std::vector<MatchedObservation> observations);

  int size() const override { return static_cast<int>(observations_.size()); }
  BlockMatrix S(int i) const override { return ekf_->InnovationCovariance(Linearised(i)); }
  BlockJacobians H(int i) const override { return Linearised(i).H; }
  BlockMatrix R(int i) const override { return observations_[i].R; }
  bool applied(int i) const override { return applied_[i] != 0; }
  void Apply(int i) override;

 private:
  Linearisation Linearised(int i) const;

  BlockEkf* ekf_;
  std::vector<MatchedObservation> observations_;
  std::vector<char> applied_;
};

}  // namespace slamkit
