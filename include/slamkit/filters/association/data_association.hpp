#pragma once

#include <limits>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

struct AssociationParams {
  // Squared Mahalanobis distance under which an observation matches a landmark
  // (χ²₂ at 99 %: 9.21).
  double gate_chi2 = 9.21;
  // Above this distance to every landmark an observation starts a new landmark (χ²₂ at 99.9 %:
  // 13.82); between the two gates it is ambiguous and dropped.
  double new_landmark_chi2 = 13.82;
};

// A landmark the filter considered for an observation, with its squared Mahalanobis distance
// νᵀ S⁻¹ ν (SPEC S2, Eqs. 6-7).
struct AssociationCandidate {
  int landmark = -1;
  double distance_chi2 = 0.0;
};

struct AssociationDecision {
  enum class Kind { kMatched, kNew, kDropped };
  Kind kind = Kind::kDropped;
  int landmark = -1;          // the matched or created landmark's index, -1 when dropped
  // To the matched landmark; when none matched, to the nearest candidate (infinity if none).
  double distance_chi2 = 0.0;
};

// A pairing hypothesis for a joint-compatibility test: observation `observation` of the scan
// produced by landmark `landmark`.
struct Pairing {
  int observation = -1;
  int landmark = -1;
};

// The joint innovation of a hypothesis: the stacked innovations and their joint covariance
// (Neira & Tardós 2001: D² = νᵀ S⁻¹ ν against a χ² bound with the stacked dimension).
struct JointInnovation {
  Eigen::VectorXd nu;
  Eigen::MatrixXd S;
};

// A scan's observations as an associator sees them, against the filter's current posterior.
class AssociationContext {
 public:
  virtual ~AssociationContext() = default;

  virtual int NumObservations() const = 0;
  virtual const PointObservation& Observation(int i) const = 0;
  virtual int NumLandmarks() const = 0;
  // The landmarks that pass the observation model's gate for observation i and that no earlier
  // part of this scan took, in landmark order, with their squared Mahalanobis distances.
  virtual std::span<const AssociationCandidate> Candidates(int i) const = 0;
  // The landmark created from observation id `id`, or -1.
  virtual int LandmarkWithSourceId(LandmarkId id) const = 0;
  // Squared Mahalanobis distance of observation i from landmark `landmark`.
  virtual double Distance(int i, int landmark) const = 0;
  virtual JointInnovation Joint(std::span<const Pairing> hypothesis) const = 0;
};

// Decides which landmark produced each observation of a scan.
class Associator {
 public:
  virtual ~Associator() = default;
  // One decision per observation, in order; kNew decisions carry landmark -1.
  virtual std::vector<AssociationDecision> Associate(const AssociationContext& scan) = 0;
};

// SPEC S2, Eqs. 6-7: nearest neighbour on the Mahalanobis distance with a χ² gate, and a second,
// larger gate that separates new landmarks from ambiguous sightings. Observations are decided in
// scan order and a landmark takes at most one sighting per scan.
class NearestNeighbourAssociator final : public Associator {
 public:
  explicit NearestNeighbourAssociator(const AssociationParams& params = {}) : params_(params) {}
  std::vector<AssociationDecision> Associate(const AssociationContext& scan) override;
  // The rule for one observation: decides from its candidates; a kNew decision carries
  // landmark -1 (the filter assigns it).
  AssociationDecision Associate(std::span<const AssociationCandidate> candidates) const;
  const AssociationParams& params() const { return params_; }

 private:
  AssociationParams params_;
  std::vector<AssociationCandidate> free_;  // scratch, reused across scans
  std::vector<char> taken_;                 // scratch, reused across scans
};

// Maximum likelihood (Thrun, Burgard & Fox 2005, Sec. 7.5 and 10.3; per particle in FastSLAM,
// Montemerlo et al. 2003, Sec. 4): among the landmarks within gate_chi2, the one under whose
// innovation density N(0, S) the observation is most likely, d² + ln|S| smallest. The new and
// ambiguous decisions are nearest neighbour's. The two differ where the candidates' S differ: a
// landmark whose prediction is uncertain lies near many sightings in Mahalanobis distance, but
// its density at any of them is low.
class MaximumLikelihoodAssociator final : public Associator {
 public:
  explicit MaximumLikelihoodAssociator(const AssociationParams& params = {}) : nearest_(params) {}
  std::vector<AssociationDecision> Associate(const AssociationContext& scan) override;

 private:
  NearestNeighbourAssociator nearest_;  // the gates
  std::vector<AssociationCandidate> free_;
  std::vector<char> taken_;
};

// Global nearest neighbour, greedy (Bar-Shalom and Fortmann 1988; Cox 1993): the scan's
// observation-landmark pairs within gate_chi2, taken in increasing distance, each observation and
// each landmark at most once. Nearest neighbour in scan order lets an observation take the
// landmark that a later, nearer one needs, which then starts a duplicate: in a dense cluster
// (landmarks under a metre apart) that is how a map doubles its landmarks (docs/scenario.md). An
// observation left unmatched starts a landmark only when it lies beyond new_landmark_chi2 from
// every landmark, taken ones included: a sighting that a landmark of the scan could explain is
// dropped, not mapped twice. Needs the whole scan at once (UpdateSchedule::kPerScan).
class GlobalNearestNeighbourAssociator final : public Associator {
 public:
  explicit GlobalNearestNeighbourAssociator(const AssociationParams& params = {})
      : params_(params) {}
  std::vector<AssociationDecision> Associate(const AssociationContext& scan) override;

 private:
  struct GatedPair {
    double distance_chi2;
    int observation;
    int landmark;
  };
  AssociationParams params_;
  std::vector<GatedPair> pairs_;  // scratch, reused across scans
};

// The observation's id names its landmark (simulator truth, a data set's association): the
// landmark created from that id, or a new one.
// A sighting farther than `gate_chi2` from its known landmark is dropped as an outlier (a
// misread or a reflection in a real log); the default, infinity, trusts every id.
class KnownAssociation final : public Associator {
 public:
  explicit KnownAssociation(double gate_chi2 = std::numeric_limits<double>::infinity())
      : gate_chi2_(gate_chi2) {}
  std::vector<AssociationDecision> Associate(const AssociationContext& scan) override;

 private:
  double gate_chi2_;
};

}  // namespace slamkit
