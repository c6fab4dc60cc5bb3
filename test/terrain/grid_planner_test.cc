// Tests for src/terrain/grid_planner.cc: rasterising, inflation, A* and the look-ahead point.
#include "vb/terrain/grid_planner.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vb/engine/rng.h"

namespace vb::terrain {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;

// Grid from rows of text: '#' blocked, anything else free. Cell size 1 m.
OccupancyGrid GridFromText(const std::vector<std::string>& rows) {
  OccupancyGrid g;
  g.rows = static_cast<int>(rows.size());
  g.cols = static_cast<int>(rows[0].size());
  g.cell_m = 1.0;
  g.size_x_m = g.cols - 1.0;
  g.size_y_m = g.rows - 1.0;
  for (const std::string& row : rows) {
    for (char ch : row) g.occupied.push_back(ch == '#' ? 1 : 0);
  }
  return g;
}

OccupancyGrid EmptyGrid(int rows, int cols) {
  return GridFromText(std::vector<std::string>(rows, std::string(cols, '.')));
}

double PathCost(const std::vector<Cell>& path) {
  double cost = 0.0;
  for (size_t i = 1; i < path.size(); ++i) {
    const int dr = std::abs(path[i].row - path[i - 1].row);
    const int dc = std::abs(path[i].col - path[i - 1].col);
    EXPECT_LE(dr, 1);
    EXPECT_LE(dc, 1);
    EXPECT_GT(dr + dc, 0);
    cost += (dr && dc) ? kSqrt2 : 1.0;
  }
  return cost;
}

// A 129 x 129 task at 1 m with the given obstacles (heights are irrelevant to rasterising).
TaskSpec ObstacleTask(const std::vector<RockSpec>& rocks, const std::vector<TreeSpec>& trees) {
  TaskSpec t;
  t.size_x_m = t.size_y_m = 128.0;
  t.heights.rows = t.heights.cols = 129;
  t.heights.heights_m.assign(129 * 129, 0.0);
  t.rocks = rocks;
  t.trees = trees;
  return t;
}

int CountOccupied(const OccupancyGrid& g) {
  int n = 0;
  for (uint8_t v : g.occupied) n += v;
  return n;
}

TEST(OccupancyGridTest, CellOfAndCenterOfRoundTrip) {
  const OccupancyGrid g = RasterizeObstacles(ObstacleTask({}, {}));
  EXPECT_EQ(g.rows, 129);
  EXPECT_DOUBLE_EQ(g.cell_m, 1.0);
  const Cell origin = g.CellOf(Vec2(0.0, 0.0));
  EXPECT_EQ(origin.row, 64);
  EXPECT_EQ(origin.col, 64);
  const Cell c = g.CellOf(Vec2(-63.6, 63.7));  // nearest vertex (-64, 64)
  EXPECT_EQ(c.row, 0);
  EXPECT_EQ(c.col, 0);
  EXPECT_EQ(g.CellOf(Vec2(500.0, -500.0)), (Cell{128, 128}));  // clamped
  const Vec2 p = g.CenterOf(Cell{10, 20});
  EXPECT_DOUBLE_EQ(p.x(), -44.0);
  EXPECT_DOUBLE_EQ(p.y(), 54.0);
  EXPECT_EQ(g.CellOf(p), (Cell{10, 20}));
}

TEST(RasterizeObstaclesTest, RockFootprintsAreThreeFiveFiveWide) {
  // scales giving w = int(4.4 * s) = 3, 4, 5 cells -> squares of 3, 5, 5 cells
  const double scales[3] = {0.7, 1.0, 1.2};
  const int expected_side[3] = {3, 5, 5};
  for (int k = 0; k < 3; ++k) {
    const OccupancyGrid g = RasterizeObstacles(ObstacleTask({{10.2, -5.3, scales[k]}}, {}));
    const Cell centre = g.CellOf(Vec2(10.2, -5.3));
    EXPECT_EQ(centre, (Cell{69, 74}));
    EXPECT_EQ(CountOccupied(g), expected_side[k] * expected_side[k]) << scales[k];
    const int half = expected_side[k] / 2;
    for (int dr = -half; dr <= half; ++dr) {
      for (int dc = -half; dc <= half; ++dc) EXPECT_TRUE(g.Occupied(69 + dr, 74 + dc));
    }
    EXPECT_FALSE(g.Occupied(69 - half - 1, 74));
    EXPECT_FALSE(g.Occupied(69, 74 + half + 1));
  }
}

TEST(RasterizeObstaclesTest, TreeIsOneCellAndBorderRocksAreClipped) {
  const OccupancyGrid g = RasterizeObstacles(ObstacleTask({{-64.0, 64.0, 1.2}}, {{3.0, 4.0}}));
  EXPECT_TRUE(g.Occupied(60, 67));
  // rock at the NW corner: only the in-grid 3 x 3 quarter of its 5 x 5 square
  EXPECT_EQ(CountOccupied(g), 1 + 9);
}

TEST(InflateTest, SquareDilation) {
  OccupancyGrid g = EmptyGrid(11, 11);
  g.occupied[5 * 11 + 5] = 1;
  g.occupied[0] = 1;
  const OccupancyGrid out = Inflate(g, 2);
  // 5 x 5 around the centre and 3 x 3 at the clipped corner, disjoint
  EXPECT_EQ(CountOccupied(out), 25 + 9);
  EXPECT_TRUE(out.Occupied(3, 3));
  EXPECT_TRUE(out.Occupied(7, 7));
  EXPECT_TRUE(out.Occupied(3, 7));
  EXPECT_TRUE(out.Occupied(2, 2));
  EXPECT_FALSE(out.Occupied(8, 5));
  EXPECT_FALSE(out.Occupied(5, 2));
  EXPECT_EQ(CountOccupied(Inflate(g, 0)), 2);
}

TEST(AStarTest, StraightLine) {
  const auto path = AStar(EmptyGrid(5, 10), {2, 1}, {2, 8});
  ASSERT_TRUE(path);
  EXPECT_EQ(path->size(), 8u);
  EXPECT_EQ(path->front(), (Cell{2, 1}));
  EXPECT_EQ(path->back(), (Cell{2, 8}));
  EXPECT_DOUBLE_EQ(PathCost(*path), 7.0);
}

TEST(AStarTest, DiagonalCostIsSqrt2AndPathIsOptimal) {
  // 3 rows and 7 columns apart: optimal octile cost 4 + 3*sqrt(2)
  const auto path = AStar(EmptyGrid(10, 10), {1, 1}, {4, 8});
  ASSERT_TRUE(path);
  EXPECT_EQ(path->size(), 8u);
  EXPECT_NEAR(PathCost(*path), 4.0 + 3.0 * kSqrt2, 1e-12);
}

TEST(AStarTest, WallWithAGap) {
  const OccupancyGrid g = GridFromText({
      "..........",
      "....#.....",
      "....#.....",
      "....#.....",
      "..........",  // the gap
      "....#.....",
      "....#.....",
  });
  const auto path = AStar(g, {1, 0}, {1, 9});
  ASSERT_TRUE(path);
  for (const Cell& c : *path) EXPECT_FALSE(g.Occupied(c.row, c.col));
  // through row 0 (around the wall's top end): 9 columns with one row of detour
  // (1,0) -> (0,1) ... -> (0,4) -> ... -> (1,9): 2 diagonals + 7 straight
  EXPECT_NEAR(PathCost(*path), 7.0 + 2.0 * kSqrt2, 1e-12);

  const OccupancyGrid closed_top = GridFromText({
      "....#.....",
      "....#.....",
      "....#.....",
      "....#.....",
      "..........",
      "....#.....",
      "....#.....",
  });
  const auto through_gap = AStar(closed_top, {0, 0}, {0, 9});
  ASSERT_TRUE(through_gap);
  bool used_gap = false;
  for (const Cell& c : *through_gap) used_gap = used_gap || (c == Cell{4, 4});
  EXPECT_TRUE(used_gap);
  // down 4 rows diagonally to the gap and back up: 8 diagonals + 1 straight
  EXPECT_NEAR(PathCost(*through_gap), 1.0 + 8.0 * kSqrt2, 1e-12);
}

TEST(AStarTest, UnreachableAndOccupiedGoal) {
  const OccupancyGrid g = GridFromText({
      "...#...",
      "...#...",
      "...#...",
  });
  EXPECT_FALSE(AStar(g, {1, 0}, {1, 6}));
  EXPECT_FALSE(AStar(g, {1, 0}, {1, 3}));  // goal occupied
  const auto same = AStar(g, {1, 3}, {1, 3});
  ASSERT_TRUE(same);
  EXPECT_EQ(same->size(), 1u);
}

TEST(AStarTest, StartInsideObstacleIsExpanded) {
  const OccupancyGrid g = GridFromText({
      ".....",
      ".###.",
      ".###.",
      ".....",
  });
  const auto path = AStar(g, {1, 2}, {3, 4});
  ASSERT_TRUE(path);
  EXPECT_EQ(path->front(), (Cell{1, 2}));
  for (size_t i = 1; i < path->size(); ++i) {
    EXPECT_FALSE(g.Occupied((*path)[i].row, (*path)[i].col));
  }
}

TEST(AStarTest, DeterministicTieBreak) {
  // many optimal paths exist on an empty grid; the result must be the same every time
  const OccupancyGrid g = EmptyGrid(20, 20);
  const auto first = AStar(g, {0, 0}, {12, 19});
  ASSERT_TRUE(first);
  for (int i = 0; i < 5; ++i) {
    const auto again = AStar(g, {0, 0}, {12, 19});
    ASSERT_TRUE(again);
    ASSERT_EQ(again->size(), first->size());
    for (size_t k = 0; k < first->size(); ++k) EXPECT_EQ((*again)[k], (*first)[k]);
  }
}

// The goal distance field gives paths exactly as cheap as A*'s (both optimal) from every start,
// on random grids with many obstacles; both agree on what is unreachable; paths are valid.
TEST(GoalDistanceFieldTest, PathsAsCheapAsAStarOnRandomGrids) {
  Rng rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    OccupancyGrid g = EmptyGrid(40, 50);
    for (uint8_t& v : g.occupied) v = rng.Uniform(0.0, 1.0) < 0.3 ? 1 : 0;
    const Cell goal{rng.UniformInt(0, 39), rng.UniformInt(0, 49)};
    const GoalDistanceField field(g, goal);
    for (int k = 0; k < 25; ++k) {
      const Cell start{rng.UniformInt(0, 39), rng.UniformInt(0, 49)};
      const auto a = AStar(g, start, goal);
      const auto f = field.PathFrom(start);
      ASSERT_EQ(a.has_value(), f.has_value()) << "trial " << trial << " start " << start.row
                                              << "," << start.col;
      if (!a) continue;
      EXPECT_NEAR(PathCost(*f), PathCost(*a), 1e-9);
      EXPECT_EQ(f->front(), start);
      EXPECT_EQ(f->back(), goal);
      for (size_t i = 1; i < f->size(); ++i) EXPECT_FALSE(g.Occupied((*f)[i].row, (*f)[i].col));
      if (!g.Occupied(start.row, start.col)) {
        EXPECT_NEAR(field.CostToGoal(start), PathCost(*f), 1e-9);
      }
    }
  }
}

TEST(GoalDistanceFieldTest, UnreachableOccupiedGoalAndStartInsideObstacle) {
  const OccupancyGrid wall = GridFromText({
      "...#...",
      "...#...",
      "...#...",
  });
  EXPECT_FALSE(GoalDistanceField(wall, {1, 6}).PathFrom(Cell{1, 0}));
  EXPECT_FALSE(GoalDistanceField(wall, {1, 3}).PathFrom(Cell{1, 0}));  // goal occupied
  EXPECT_TRUE(std::isinf(GoalDistanceField(wall, {1, 6}).CostToGoal({1, 0})));
  const OccupancyGrid block = GridFromText({
      ".....",
      ".###.",
      ".###.",
      ".....",
  });
  const auto path = GoalDistanceField(block, {3, 4}).PathFrom(Cell{1, 2});
  ASSERT_TRUE(path);
  EXPECT_EQ(path->front(), (Cell{1, 2}));
  EXPECT_NEAR(PathCost(*path), PathCost(*AStar(block, {1, 2}, {3, 4})), 1e-9);
}

TEST(PlanPathTest, WorldCoordinatesStartToGoal) {
  const OccupancyGrid g = Inflate(RasterizeObstacles(ObstacleTask({{0.0, 0.0, 1.0}}, {})), 4);
  const auto path = PlanPath(g, Vec2(-60.0, 0.2), Vec2(60.0, -0.3));
  ASSERT_TRUE(path);
  EXPECT_TRUE(path->front().isApprox(Vec2(-60.0, 0.0)));
  EXPECT_TRUE(path->back().isApprox(Vec2(60.0, 0.0)));
  for (const Vec2& p : *path) EXPECT_FALSE(std::abs(p.x()) <= 6.0 && std::abs(p.y()) <= 6.0);
}

TEST(LookAheadPointTest, FirstPointFarEnoughAndAhead) {
  std::vector<Vec2> path;
  for (int x = -10; x <= 30; ++x) path.push_back(Vec2(x, 0.0));
  size_t index = 0;
  // at the origin heading east: points behind (x < 0) are skipped even if far enough
  Vec2 p = LookAheadPoint(path, Vec2(0.0, 0.0), 0.0, 10.0, &index);
  EXPECT_TRUE(p.isApprox(Vec2(10.0, 0.0)));
  EXPECT_EQ(index, 20u);
  // heading west: the first far-enough point ahead is (-10, 0), index 0
  index = 0;
  p = LookAheadPoint(path, Vec2(0.0, 0.0), kPi, 10.0, &index);
  EXPECT_TRUE(p.isApprox(Vec2(-10.0, 0.0)));
  EXPECT_EQ(index, 0u);
  // scanning starts at *index
  index = 25;
  p = LookAheadPoint(path, Vec2(0.0, 0.0), 0.0, 10.0, &index);
  EXPECT_TRUE(p.isApprox(Vec2(15.0, 0.0)));
  // near the end nothing is far enough: the last point
  index = 0;
  p = LookAheadPoint(path, Vec2(25.0, 0.0), 0.0, 10.0, &index);
  EXPECT_TRUE(p.isApprox(Vec2(30.0, 0.0)));
  EXPECT_EQ(index, path.size() - 1);
  // bearing exactly 90 deg counts as ahead
  index = 0;
  p = LookAheadPoint({Vec2(0.0, 10.0), Vec2(0.0, 20.0)}, Vec2(0.0, 0.0), 0.0, 10.0, &index);
  EXPECT_TRUE(p.isApprox(Vec2(0.0, 10.0)));
}

}  // namespace
}  // namespace vb::terrain
