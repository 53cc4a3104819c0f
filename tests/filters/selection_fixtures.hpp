#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/selection/selection.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit::testing {

// A random small SLAM state on a BlockEkf: a pose and `landmarks` range-bearing landmarks, each
// added from the pose and followed by an odometry step, so that all blocks are correlated.
class RandomSlamState {
 public:
  RandomSlamState(int landmarks, std::uint64_t seed)
      : ekf(16), point_kind(ekf.RegisterKind({2, {}, false})), model(sensor, point_kind, 5.0),
        rng(seed) {
    const double x = rng.Uniform(-1, 1), y = rng.Uniform(-1, 1);
    const Pose2 start(x, y, rng.Uniform(-3, 3));
    ekf.AddBlock(kPoseKind, start.vector(), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
    const OdometryModel odometry;
    for (int i = 0; i < landmarks; ++i) {
      const double range = rng.Uniform(2.0, 20.0);
      const Eigen::Vector2d z(range, rng.Uniform(-3.0, 3.0));
      const int observers[] = {kPoseKind};
      blocks.push_back(AugmentFrom(model, ekf, observers, z, sensor.NoiseCovariance()));
      Control u(3);
      u[0] = rng.Uniform(0.2, 1.0);
      u[1] = rng.Uniform(-0.1, 0.1);
      u[2] = rng.Uniform(-0.3, 0.3);
      Eigen::Matrix3d F;
      ControlJacobian G;
      const Pose2 moved = odometry.Move(ekf.PoseOf(0), u, 0.1, &F, &G);
      ekf.PredictPose(0, moved, F, G, odometry.Noise(u, 0.1));
    }
  }
  RandomSlamState(const RandomSlamState&) = delete;

  // A fresh noisy sighting of each landmark (or of the first `count`) from the current mean.
  std::vector<MatchedObservation> Sightings(int count = -1) {
    std::vector<MatchedObservation> out;
    const Eigen::Matrix2d R = sensor.NoiseCovariance();
    for (int k = 0; k < (count < 0 ? static_cast<int>(blocks.size()) : count); ++k) {
      const int observed[] = {kPoseKind, blocks[k]};
      Eigen::Vector2d z = model.Predict(ekf, observed).z;
      z[0] += rng.Normal(0.0, 0.1);
      z[1] += rng.Normal(0.0, 0.0175);
      out.push_back({&model, {kPoseKind, blocks[k]}, 2, z, R});
    }
    return out;
  }

  RangeBearingModel sensor;
  BlockEkf ekf;
  int point_kind;
  PointLandmarkModel model;
  Rng rng;
  std::vector<int> blocks;
};

// A direct fix of one point block, z = l: S_i is that block's covariance plus R.
class PointFixModel final : public ObservationModel {
 public:
  int MeasurementDim() const override { return 2; }
  BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const override {
    BlockPrediction p;
    p.z = ekf.Mean(blocks[0]);
    p.J_z_blocks.Add(blocks[0], Eigen::Matrix2d::Identity());
    return p;
  }
  BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const override {
    return z - z_pred;
  }
};

inline double DenseLogDet(const Eigen::MatrixXd& P) { return std::log(P.determinant()); }

// Forwards to a session and records what the policy did: the order of Apply() calls and, at
// each, LogSensitivity() of every observation (−∞ for the applied ones).
class RecordingSession final : public SelectionSession {
 public:
  explicit RecordingSession(SelectionSession& inner) : inner_(&inner) {}
  int size() const override { return inner_->size(); }
  BlockMatrix S(int i) const override { return inner_->S(i); }
  BlockJacobians H(int i) const override { return inner_->H(i); }
  BlockMatrix R(int i) const override { return inner_->R(i); }
  bool applied(int i) const override { return inner_->applied(i); }
  double LogDetCovariance() const override { return inner_->LogDetCovariance(); }
  double LogDetAfter(int i) const override { return inner_->LogDetAfter(i); }
  void Apply(int i) override {
    std::vector<double> scores(size(), -std::numeric_limits<double>::infinity());
    for (int j = 0; j < size(); ++j) {
      if (!applied(j)) scores[j] = LogSensitivity(*inner_, j);
    }
    scores_at_apply.push_back(scores);
    order.push_back(i);
    inner_->Apply(i);
  }

  std::vector<int> order;
  std::vector<std::vector<double>> scores_at_apply;

 private:
  SelectionSession* inner_;
};

// Runs `inner` on a RecordingSession and keeps, step by step, the order it applied.
class RecordedPolicy final : public SelectionPolicy {
 public:
  explicit RecordedPolicy(std::unique_ptr<SelectionPolicy> inner) : inner_(std::move(inner)) {}
  void Select(SelectionSession& session) override {
    RecordingSession recording(session);
    inner_->Select(recording);
    steps.push_back(recording.order);
  }
  std::vector<std::vector<int>> steps;

 private:
  std::unique_ptr<SelectionPolicy> inner_;
};

}  // namespace slamkit::testing
