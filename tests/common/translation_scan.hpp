#pragma once

#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "slamkit/filters/association/data_association.hpp"

namespace slamkit::testing {

// A scan of point landmarks seen as z = l - x (translation only) from a pose known only to
// N(x_hat, Px), each landmark known to N(l, P_l) independently of the pose, with noise R. Every
// innovation carries the same pose error, so the innovations of one scan are correlated through
// Px, as in EKF-SLAM; the landmarks' own covariances make their S differ.
class TranslationScan final : public AssociationContext {
 public:
  // `landmark_covariances` empty: landmarks known exactly.
  TranslationScan(std::vector<Eigen::Vector2d> landmarks, std::vector<PointObservation> z,
                  const Eigen::Vector2d& x_hat, const Eigen::Matrix2d& Px,
                  std::vector<Eigen::Matrix2d> landmark_covariances = {})
      : landmarks_(std::move(landmarks)),
        P_landmark_(std::move(landmark_covariances)),
        z_(std::move(z)),
        x_hat_(x_hat),
        Px_(Px) {
    if (P_landmark_.empty()) P_landmark_.assign(landmarks_.size(), Eigen::Matrix2d::Zero());
  }

  int NumObservations() const override { return static_cast<int>(z_.size()); }
  const PointObservation& Observation(int i) const override { return z_[i]; }
  int NumLandmarks() const override { return static_cast<int>(landmarks_.size()); }
  std::span<const AssociationCandidate> Candidates(int i) const override {
    scratch_.clear();
    for (int l = 0; l < NumLandmarks(); ++l) scratch_.push_back({l, Distance(i, l)});
    return scratch_;
  }
  int LandmarkWithSourceId(LandmarkId) const override { return -1; }
  double Distance(int i, int l) const override {
    const Eigen::Vector2d nu = Innovation(i, l);
    return nu.dot((Px_ + P_landmark_[l] + z_[i].R).inverse() * nu);
  }
  JointInnovation Joint(std::span<const Pairing> h) const override {
    const int k = static_cast<int>(h.size());
    JointInnovation j;
    j.nu.resize(2 * k);
    j.S = Eigen::MatrixXd::Zero(2 * k, 2 * k);
    for (int a = 0; a < k; ++a) {
      j.nu.segment<2>(2 * a) = Innovation(h[a].observation, h[a].landmark);
      for (int b = 0; b < k; ++b) {
        j.S.block<2, 2>(2 * a, 2 * b) = Px_;
        if (h[a].landmark == h[b].landmark) {
          j.S.block<2, 2>(2 * a, 2 * b) += P_landmark_[h[a].landmark];
        }
      }
      j.S.block<2, 2>(2 * a, 2 * a) += z_[h[a].observation].R;
    }
    return j;
  }

 private:
  Eigen::Vector2d Innovation(int i, int l) const { return z_[i].z - (landmarks_[l] - x_hat_); }

  std::vector<Eigen::Vector2d> landmarks_;
  std::vector<Eigen::Matrix2d> P_landmark_;
  std::vector<PointObservation> z_;
  Eigen::Vector2d x_hat_;
  Eigen::Matrix2d Px_;
  mutable std::vector<AssociationCandidate> scratch_;
};

}  // namespace slamkit::testing
