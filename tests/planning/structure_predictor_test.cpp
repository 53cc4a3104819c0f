#include "slamkit/planning/structure_predictor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/rng.hpp"
#include "common/grid_drawing.hpp"

namespace slamkit::structure_predictor_test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRes = 0.1;     // the grid of SPEC S4
constexpr double kSplit = 2.95;  // the partial room is explored this far along its first wall
const float kOccupied = static_cast<float>(std::log(0.65 / 0.35));  // the default threshold
using Corners = std::array<Eigen::Vector2d, 4>;

OccupancyGrid MakeGrid() { return OccupancyGrid(OccupancyGridParams{kRes}); }

using testing::DrawWall;

// A w × h room with its lower-left corner at `origin`, turned by `angle` about it: walls
// occupied, the inside free; its corners counter-clockwise from the origin.
Corners DrawRoom(OccupancyGrid& grid, const Eigen::Vector2d& origin, double angle, double w,
                 double h) {
  const Eigen::Rotation2Dd R(angle);
  const Corners c = {origin, origin + R * Eigen::Vector2d(w, 0.0),
                     origin + R * Eigen::Vector2d(w, h), origin + R * Eigen::Vector2d(0.0, h)};
  for (int i = 0; i < 4; ++i) DrawWall(grid, c[i], c[(i + 1) % 4]);
  const double reach = w + h;
  const CellIndex lo = grid.WorldToCell(origin - Eigen::Vector2d(reach, reach));
  const CellIndex hi = grid.WorldToCell(origin + Eigen::Vector2d(reach, reach));
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      const Eigen::Vector2d q = R.inverse() * (grid.CellCenter({x, y}) - origin);
      const double m = 0.5 * kRes;
      if (q.x() > m && q.x() < w - m && q.y() > m && q.y() < h - m) grid.Update({x, y}, -2.0f);
    }
  }
  return c;
}

bool OccupiedWithin1(const OccupancyGrid& g, const CellIndex& c) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (g.LogOdds({c.x + dx, c.y + dy}) > kOccupied) return true;
    }
  }
  return false;
}

// Room A (a_w × a_h, a reference explored in full) and room B (6 × 4, a copy of the 6 × 4 room
// turned by `turn`) explored up to kSplit along its first wall; f a free cell on B's frontier.
// Everything is moved by `frame`. `truth` holds both rooms complete. With `hall`, A stands in an
// explored hall of free floor 16 m wide, which reaches beyond the corners of the box around f.
struct Scene {
  OccupancyGrid truth = MakeGrid();
  OccupancyGrid map = MakeGrid();
  Corners a, b;
  Eigen::Vector2d f;
};

Scene MakeScene(double turn, const Eigen::Vector2d& b_origin, const Pose2& frame = {},
                double a_w = 6.0, double a_h = 4.0, bool hall = false) {
  Scene s;
  for (int y = -40; hall && y < 100; ++y) {
    for (int x = -40; x < 120; ++x) s.truth.Update({x, y}, -2.0f);
  }
  s.a = DrawRoom(s.truth, frame.TransformFrom({1.05, 1.05}), frame.theta(), a_w, a_h);
  const Eigen::Vector2d o = frame.TransformFrom(b_origin);
  const double angle = frame.theta() + turn;
  s.b = DrawRoom(s.truth, o, angle, 6.0, 4.0);
  const Eigen::Rotation2Dd R(angle);
  s.f = o + R * Eigen::Vector2d(kSplit - 0.05, 1.5);
  ForEachKnownCell(s.truth, [&](const CellIndex& c, OccupancyGrid::CellValue v) {
    const Eigen::Vector2d q = R.inverse() * (s.truth.CellCenter(c) - o);
    const bool in_b = q.x() > -0.2 && q.x() < 6.2 && q.y() > -0.2 && q.y() < 4.2;
    if (!in_b || q.x() < kSplit) s.map.UpdateSteps(c, v);
  });
  return s;
}

TEST(StructurePredictor, ControlPointAlignmentTakesTheReferenceOntoTheTargetTurnedByTheta) {
  Rng rng(3);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector2d target(rng.Uniform(-20, 20), rng.Uniform(-20, 20));
    const Eigen::Vector2d reference(rng.Uniform(-20, 20), rng.Uniform(-20, 20));
    const Eigen::Vector2d d(rng.Uniform(-3, 3), rng.Uniform(-3, 3));
    const double theta = rng.Uniform(-4.0, 4.0);
    const Pose2 g = ControlPointAlignment(target, reference, theta);
    EXPECT_LT((g.TransformFrom(reference) - target).norm(), 1e-9);
    EXPECT_NEAR(WrapAngle(g.theta() - theta), 0.0, 1e-12);
    EXPECT_LT((g.TransformFrom(reference + d) - target - Eigen::Rotation2Dd(theta) * d).norm(),
              1e-9);
  }
  // By hand: a quarter turn takes the point 1 m east of the reference 1 m north of the target.
  const Pose2 g = ControlPointAlignment({1.0, 2.0}, {3.0, 4.0}, kPi / 2.0);
  EXPECT_LT((g.TransformFrom({4.0, 4.0}) - Eigen::Vector2d(1.0, 3.0)).norm(), 1e-12);
}

TEST(StructurePredictor, AlignedSimilarityIsOneForTheRightAlignmentAndLowForWrongOnes) {
  // B is A turned by a quarter turn about its first corner and moved: exactly
  // x ↦ R(π/2)(x − a0) + b0.
  const Scene s = MakeScene(kPi / 2.0, {24.05, 1.05});
  const StructurePredictorParams p;
  const Eigen::Vector2d centre_a = 0.25 * (s.a[0] + s.a[1] + s.a[2] + s.a[3]);
  const Eigen::Vector2d centre_b = 0.25 * (s.b[0] + s.b[1] + s.b[2] + s.b[3]);
  EXPECT_DOUBLE_EQ(AlignedSimilarity(s.truth, centre_a, 5.0, Pose2(), p), 1.0);
  EXPECT_DOUBLE_EQ(AlignedSimilarity(MakeGrid(), centre_a, 5.0, Pose2(), p), 0.0);
  const Pose2 right = ControlPointAlignment(s.b[0], s.a[0], kPi / 2.0);
  EXPECT_GT(AlignedSimilarity(s.truth, centre_b, 5.0, right, p), 0.95);
  EXPECT_GT(AlignedSimilarity(s.truth, centre_a, 5.0, right.Inverse(), p), 0.95);
  // One cell off along both axes: every wall lands beside its match, which the one-cell tolerance
  // accepts and Eq. 5 exactly (tolerance 0) does not.
  const Pose2 one_cell =
      ControlPointAlignment(s.b[0] + Eigen::Vector2d(kRes, kRes), s.a[0], kPi / 2.0);
  StructurePredictorParams exact = p;
  exact.tolerance_cells = 0;
  EXPECT_GT(AlignedSimilarity(s.truth, centre_b, 5.0, one_cell, p), 0.95);
  EXPECT_LT(AlignedSimilarity(s.truth, centre_b, 5.0, one_cell, exact), 0.1);
  EXPECT_GT(AlignedSimilarity(s.truth, centre_b, 5.0, right, exact), 0.95);
  // The same corners without the turn, the turn the wrong way, and the right one off by 0.5 m.
  for (const auto& [shift, theta] : {std::pair{0.0, 0.0}, {0.0, -kPi / 2.0}, {0.5, kPi / 2.0}}) {
    const Pose2 wrong =
        ControlPointAlignment(s.b[0] + Eigen::Vector2d(shift, shift), s.a[0], theta);
    EXPECT_LT(AlignedSimilarity(s.truth, centre_b, 5.0, wrong, p), 0.5) << shift << " " << theta;
  }
}

// The properties of an accepted prediction for a partial copy of a fully explored room.
void ExpectPredictsTheMissingHalf(const Scene& s) {
  const StructurePredictorParams p;
  const double radius = 0.5 * p.region_diameter_m;
  const std::optional<PredictedStructure> r = PredictStructure(s.map, s.f, p);
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->accepted);
  const GridHypothesis& h = r->hypothesis;
  EXPECT_GE(h.similarity, p.similarity_threshold);
  EXPECT_GT(h.similarity, 0.9);  // an exact copy: every wall cell has its match
  EXPECT_EQ(h.target_m, s.f);
  // The control point is the explored corner of B nearest f (b0 for this f).
  EXPECT_LT((h.control_point_m - s.b[0]).norm(), 0.15);
  // Γ takes room A onto room B (as a set of corners: a rectangle is symmetric under a half turn).
  const Pose2 g = ControlPointAlignment(h.control_point_m, h.reference_point_m, h.rotation_rad);
  for (const Eigen::Vector2d& a : s.a) {
    double nearest = 1e9;
    const Eigen::Vector2d moved = g.TransformFrom(a);
    for (const Eigen::Vector2d& b : s.b) nearest = std::min(nearest, (b - moved).norm());
    EXPECT_LT(nearest, 0.2);
  }
  int known = 0, occupied = 0, free_known = 0, free_on_free = 0;
  ForEachKnownCell(h.cells, [&](const CellIndex& c, OccupancyGrid::CellValue) {
    ++known;
    EXPECT_FALSE(s.map.IsKnown(c));
    EXPECT_LE((h.cells.CellCenter(c) - s.f).norm(), radius + 1e-9);
    if (h.cells.LogOdds(c) > kOccupied) {
      ++occupied;
      EXPECT_TRUE(OccupiedWithin1(s.truth, c)) << c.x << " " << c.y;  // on a missing wall
    } else {
      free_known += s.truth.IsKnown(c);  // B's outside is unknown in the truth too
      free_on_free += s.truth.LogOdds(c) < 0.0f;
    }
  });
  EXPECT_EQ(known, h.predicted_cells);
  EXPECT_EQ(occupied, h.occupied_cells);
  EXPECT_GT(free_known, 500);  // B's missing floor, 2.9 × 3.9 m
  EXPECT_GT(free_on_free, 0.95 * free_known);
  // Nearly every missing wall cell of B is predicted (within a cell).
  int missing = 0, found = 0;
  ForEachKnownCell(s.truth, [&](const CellIndex& c, OccupancyGrid::CellValue) {
    if (s.map.IsKnown(c) || s.truth.LogOdds(c) <= kOccupied) return;
    if ((s.truth.CellCenter(c) - s.f).norm() > radius) return;
    ++missing;
    found += OccupiedWithin1(h.cells, c);
  });
  EXPECT_GT(missing, 80);  // the far end wall and half of the two side walls
  EXPECT_GT(found, 0.9 * missing);
}

TEST(StructurePredictor, PredictsTheUnexploredHalfOfACopiedRoom) {
  ExpectPredictsTheMissingHalf(MakeScene(0.0, {15.05, 1.05}));
  ExpectPredictsTheMissingHalf(MakeScene(0.0, {15.05, 1.05}, Pose2(), 6.0, 4.0, true));
}

TEST(StructurePredictor, PredictsTheUnexploredHalfOfACopyTurnedByAQuarterTurn) {
  ExpectPredictsTheMissingHalf(MakeScene(kPi / 2.0, {24.05, 1.05}));
}

TEST(StructurePredictor, NoControlPointOrNoOtherCornerGivesNone) {
  const Scene s = MakeScene(0.0, {15.05, 1.05});
  StructurePredictorParams p;
  p.control_point_range_m = 1.0;  // B's explored corners are 3.3 m and more from f
  EXPECT_FALSE(PredictStructure(s.map, s.f, p).has_value());
  // A single L of walls around explored floor: a control point but no other corner.
  OccupancyGrid l = MakeGrid();
  DrawWall(l, {0.05, 0.05}, {4.05, 0.05});
  DrawWall(l, {0.05, 0.05}, {0.05, 4.05});
  for (int i = 0; i < 39 * 39; ++i) l.Update({1 + i % 39, 1 + i / 39}, -2.0f);
  EXPECT_FALSE(PredictStructure(l, {2.05, 2.05}).has_value());
  // Too little structure around f.
  StructurePredictorParams sparse;
  sparse.min_structure_cells = 100000;
  EXPECT_FALSE(PredictStructure(s.map, s.f, sparse).has_value());
}

TEST(StructurePredictor, ADissimilarReferenceIsNotAccepted) {
  // The only fully explored room is a 2 × 2 m square: no alignment explains B's 6 × 4 m walls.
  // B's other explored corner (4 m from the control point) is kept out: turned onto the control
  // point it aligns B's explored half with itself, which Eq. 5 scores 0.75.
  const Scene s = MakeScene(0.0, {15.05, 1.05}, Pose2(), 2.0, 2.0);
  StructurePredictorParams p;
  p.min_reference_distance_m = 5.0;
  p.min_predicted_cells = 0;  // the threshold alone must turn it down
  const std::optional<PredictedStructure> r = PredictStructure(s.map, s.f, p);
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(r->accepted);
  EXPECT_LT(r->hypothesis.similarity, p.similarity_threshold);
  EXPECT_GT(r->hypothesis.alignments, 0);
  EXPECT_EQ(r->hypothesis.predicted_cells, 0);
  EXPECT_GT(r->hypothesis.cells.min_cell().x, r->hypothesis.cells.max_cell().x);  // none written
}

TEST(StructurePredictor, BudgetBoundsTheAlignmentsTried) {
  const Scene s = MakeScene(0.0, {15.05, 1.05});
  StructurePredictorParams p;
  const std::optional<PredictedStructure> all = PredictStructure(s.map, s.f, p);
  ASSERT_TRUE(all.has_value());
  // A's 4 corners and B's other explored corner, 4 pairings of arms each.
  EXPECT_EQ(all->hypothesis.alignments, 4 * 5);
  p.max_candidates = 1;
  const std::optional<PredictedStructure> one = PredictStructure(s.map, s.f, p);
  ASSERT_TRUE(one.has_value());
  EXPECT_EQ(one->hypothesis.alignments, 4);
  // Only corners within the search radius of f are candidates: B's own is, A's are not.
  p.max_candidates = 100;
  p.search_radius_m = 8.0;
  const std::optional<PredictedStructure> near = PredictStructure(s.map, s.f, p);
  ASSERT_TRUE(near.has_value());
  EXPECT_EQ(near->hypothesis.alignments, 4);
}

TEST(StructurePredictor, HypothesisSimilarityScoresThePredictionAgainstTheLaterMap) {
  const Scene s = MakeScene(0.0, {15.05, 1.05});
  const std::optional<PredictedStructure> r = PredictStructure(s.map, s.f);
  ASSERT_TRUE(r.has_value() && r->accepted);
  const GridHypothesis& h = r->hypothesis;
  const std::optional<double> right = HypothesisSimilarity(h, Pose2(), s.truth);
  ASSERT_TRUE(right.has_value());
  EXPECT_GT(*right, 0.8);
  // The same world seen in another frame: the hypothesis re-posed into it scores the same.
  const Pose2 frame(3.0, -2.0, kPi / 2.0);
  const std::optional<double> moved =
      HypothesisSimilarity(h, frame, MakeScene(0.0, {15.05, 1.05}, frame).truth);
  ASSERT_TRUE(moved.has_value());
  EXPECT_GT(*moved, 0.8);
  // B was really 1 m further up and right: its walls cross the predicted floor, and the predicted
  // walls fall on its floor.
  OccupancyGrid wrong = MakeGrid();
  DrawRoom(wrong, {1.05, 1.05}, 0.0, 6.0, 4.0);
  DrawRoom(wrong, {16.05, 2.05}, 0.0, 6.0, 4.0);
  const std::optional<double> low = HypothesisSimilarity(h, Pose2(), wrong);
  ASSERT_TRUE(low.has_value());
  EXPECT_LT(*low, 0.3);
  // Two partitions across B's far half that the hypothesis has as floor: the map's side of Eq. 5.
  OccupancyGrid partitioned = s.truth;
  DrawWall(partitioned, {19.05, 1.05}, {19.05, 5.05});
  DrawWall(partitioned, {20.05, 1.05}, {20.05, 5.05});
  const std::optional<double> walled = HypothesisSimilarity(h, Pose2(), partitioned);
  ASSERT_TRUE(walled.has_value());
  EXPECT_LT(*walled, *right - 0.15);
  // Nothing of it explored yet: the map it came from, an empty map.
  EXPECT_FALSE(HypothesisSimilarity(h, Pose2(), s.map).has_value());
  EXPECT_FALSE(HypothesisSimilarity(h, Pose2(), MakeGrid()).has_value());
}

TEST(StructurePredictor, MadePredictorUsesTheRequestsTargetOrTheNearestFrontier) {
  const Scene s = MakeScene(0.0, {15.05, 1.05});
  const StructurePredictorParams p;
  const StructurePredictor predict = MakeStructurePredictor(p);
  StructurePredictionRequest request{
      .id = 1, .t_s = 12.5, .map = s.map, .pose = Pose2(16.5, 3.0, 0.0), .target_m = s.f};
  const std::optional<PredictedStructure> given = predict(request);
  const std::optional<PredictedStructure> direct = PredictStructure(s.map, s.f, p);
  ASSERT_TRUE(given.has_value() && direct.has_value());
  EXPECT_EQ(given->hypothesis.t_s, 12.5);
  EXPECT_EQ(given->accepted, direct->accepted);
  EXPECT_EQ(given->hypothesis.similarity, direct->hypothesis.similarity);
  EXPECT_EQ(given->hypothesis.predicted_cells, direct->hypothesis.predicted_cells);
  // Without a target: the nearest reachable frontier cell, on B's open side.
  const std::optional<Eigen::Vector2d> f = ChoosePredictionTarget(s.map, request.pose, p);
  ASSERT_TRUE(f.has_value());
  EXPECT_TRUE(IsFrontierCell(s.map, s.map.WorldToCell(*f), p.frontiers));
  EXPECT_NEAR(f->x(), s.f.x(), 1e-9);
  request.target_m.reset();
  const std::optional<PredictedStructure> chosen = predict(request);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(chosen->hypothesis.target_m, *f);
  EXPECT_TRUE(chosen->accepted);
  // A target with no corner near it: no structure, and the result says where it looked.
  request.target_m = Eigen::Vector2d(60.0, 60.0);
  const std::optional<PredictedStructure> bare = predict(request);
  ASSERT_TRUE(bare.has_value());
  EXPECT_FALSE(bare->structure_found);
  EXPECT_FALSE(bare->accepted);
  EXPECT_EQ(bare->hypothesis.target_m, Eigen::Vector2d(60.0, 60.0));
  EXPECT_TRUE(chosen->structure_found);
  request.target_m.reset();
  // A map without frontiers: nothing to predict.
  OccupancyGrid closed = MakeGrid();
  DrawRoom(closed, {1.05, 1.05}, 0.0, 6.0, 4.0);
  request.map = closed;
  request.pose = Pose2(3.0, 3.0, 0.0);
  EXPECT_FALSE(predict(request).has_value());
}

}  // namespace
}  // namespace slamkit::structure_predictor_test
