#pragma once

// BlockEkf's compressed area (Guivant & Nebot, IEEE T-RA 2001, Sec. III), private to the EKF.
//
// While an area is open, the active blocks A live in a filter of their own (`local`) together
// with auxiliary blocks Z, one per active block and of its size, whose cross-covariance with A
// starts as the identity, and whose mean and covariance start at zero. Every change the area's
// filter makes to A (a prediction's F, an update's I − KH, an augmentation's J, a block's
// normalisation) applies to A's cross-covariance with any other variable the same way, so Z
// carries the paper's auxiliary matrices without new update code:
//   Cov(A, Z) = φ,  Cov(Z, Z) = −ψ,  mean(Z) = θ   (the paper's Eqs. 19-21),
// and with C = P_{B,A₀} at compression the rest of the state is, at any time,
//   x_B = x_B⁰ + C θ,  P_{A,B} = φ Cᵀ,  P_BB = P_BB⁰ − C ψ Cᵀ   (Eqs. 22-24).

#include <Eigen/Core>
#include <span>
#include <vector>

#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

struct BlockEkf::CompressedArea {
  BlockEkf local;            // [A₀ | Z | blocks added since], in that order
  std::vector<int> local_of;  // per block of the whole state: its block in `local`, or −1
  std::vector<int> a0_index;  // the whole state's indices of A₀'s entries, in local order
  int a0 = 0;                 // A₀'s size; Z occupies local entries [a0, 2·a0)
  int k0 = 0;                 // A₀'s blocks; Z's are local blocks [k0, 2·k0)
  int n0 = 0;                 // the whole state's size at compression (B ∪ A₀)

  void StartLocal(const BlockEkf& whole, std::span<const int> active);
  // C_b: block `b`'s rows of P⁰ against A₀ (d × a0), gathered from the stored triangle.
  Eigen::MatrixXd CrossRows(const BlockEkf& whole, int b) const {
    const int o = whole.blocks_[b].offset, d = whole.blocks_[b].dim;
    Eigen::MatrixXd rows(d, a0);
    for (int r = 0; r < d; ++r) {
      for (int j = 0; j < a0; ++j) {
        const int i = o + r, k = a0_index[j];
        rows(r, j) = i <= k ? whole.P_(i, k) : whole.P_(k, i);
      }
    }
    return rows;
  }
  // C over the whole state at compression (n0 × a0), A₀'s rows zero.
  Eigen::MatrixXd CrossRowsOfAll(const BlockEkf& whole) const {
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n0, a0);
    for (int b = 0; b < static_cast<int>(local_of.size()); ++b) {
      const Block& block = whole.blocks_[b];
      if (local_of[b] < 0 && block.offset < n0) {
        C.middleRows(block.offset, block.dim) = CrossRows(whole, b);
      }
    }
    return C;
  }
  Eigen::VectorXd Theta() const { return local.x_.segment(a0, a0); }
  Eigen::MatrixXd Psi() const { return -local.CurrentRange(a0, a0, a0, a0); }
  // φ's rows of local block `lb`: Cov(lb, Z).
  Eigen::MatrixXd Phi(int lb) const {
    return local.CurrentRange(local.BlockOffset(lb), local.BlockDim(lb), a0, a0);
  }
};

}  // namespace slamkit
