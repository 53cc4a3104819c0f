#pragma once

#include <limits>
#include <numbers>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/features/line_fit.hpp"
#include "slamkit/models/line_sensor.hpp"

namespace slamkit {

// Line and corner extraction from one scan (SPEC S1). The defaults suit a SICK LMS-like laser
// (1° beams, about 1 cm range noise) in an indoor environment.
struct LineExtractionParams {
  // Beams at or beyond this range are not used, besides the scan's own no-return beams (SPEC S1
  // uses 10 m of a 30 m laser). Infinity: every return of the scan.
  double max_usable_range_m = std::numeric_limits<double>::infinity();
  // Consecutive returns farther apart than this start a new run (a door, an occlusion edge).
  double max_gap_m = 0.5;
  // Iterative end-point fit: a run is split at its point farthest from the chord between its
  // end points while that distance exceeds this.
  double split_distance_m = 0.05;
  // Adjacent segments of one run are merged when their fitted lines differ by less than this
  // angle and their difference (Δρ, Δα) is within this squared Mahalanobis distance of zero
  // under the two fits' covariances (13.8: the 99.9 % quantile of χ²(2)), and the joint fit still
  // passes max_residual_rms_m.
  double merge_max_angle_rad = 0.1;
  double merge_max_mahalanobis2 = 13.8;
  // Segments with fewer points, shorter (end point to end point) or with a larger RMS residual
  // are rejected (a piece with fewer points first gives them to a neighbouring segment they fit).
  int min_points = 6;
  double min_length_m = 0.4;
  double max_residual_rms_m = 0.03;
  // Per-beam noise the line covariances are propagated from.
  double sigma_range_m = 0.01;
  double sigma_bearing_rad = 0.001;
  // Added to each extracted line's covariance (ρ, α): how far a real wall departs from the
  // straight line the fit assumes (bends, clutter along it, the laser's bias), which the beam
  // noise, averaged over many returns, does not cover. Zero: the walls are straight.
  double wall_sigma_rho_m = 0.0;
  double wall_sigma_alpha_rad = 0.0;
  // Corners: adjacent lines whose interior angle (between the two segments, at their
  // intersection) lies in [min, max], and whose near end points are both within
  // max_corner_endpoint_distance_m of the intersection. That distance must exceed the beam
  // spacing on a wall seen at a grazing angle (1° beams at 6.6 m and 63° incidence: 0.25 m).
  double min_corner_angle_rad = std::numbers::pi / 4.0;
  double max_corner_angle_rad = 3.0 * std::numbers::pi / 4.0;
  double max_corner_endpoint_distance_m = 0.5;
};

// A line segment extracted from one scan, in the sensor frame.
struct LineSegment {
  PolarLine line;                                        // the TLS fit, ρ ≥ 0
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // of (ρ [m], α [rad])
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();     // first point projected onto the line
  Eigen::Vector2d end_m = Eigen::Vector2d::Zero();       // last point (in beam order), projected
  int first_beam = 0;
  int last_beam = 0;
  int num_points = 0;
  double residual_rms_m = 0.0;

  double LengthM() const { return (end_m - start_m).norm(); }
};

// A half-open range [begin, end) of indices into a BeamPoint sequence.
struct PointRange {
  int begin = 0;
  int end = 0;
  int size() const { return end - begin; }
};

// SPEC S1, feature extraction, step 1: the usable returns of `scan` in beam order (no-return, NaN,
// non-positive and max-range beams, and beams beyond max_usable_range_m, are dropped).
std::vector<BeamPoint> ScanToBeamPoints(const LaserScan& scan, double max_usable_range_m);

// Step 2: contiguous runs of `points`, broken where consecutive points are more than max_gap_m
// apart. Beams dropped in step 1 do not break a run by themselves: a wall with a few no-return
// beams stays one run, a door (or anything seen through it) does not.
std::vector<PointRange> SplitAtGaps(std::span<const BeamPoint> points, double max_gap_m);

// Step 3 (the "split" of split-and-merge, iterative end-point fit): `run` cut recursively at its
// point farthest from the chord of its end points while that distance exceeds split_distance_m.
// The pieces are disjoint, in order, and cover `run`.
std::vector<PointRange> SplitByEndpointFit(std::span<const BeamPoint> points, PointRange run,
                                           double split_distance_m);

// All steps: split at gaps and by end-point fit, give the points of pieces too small to keep to
// the neighbour they fit, merge adjacent collinear pieces, settle which wall the points at a
// corner belong to (leaving out of both a point within 3σ of either line), reject unsupported
// segments. Segments come in beam order.
std::vector<LineSegment> ExtractLines(const LaserScan& scan, const LineExtractionParams& params);

}  // namespace slamkit
