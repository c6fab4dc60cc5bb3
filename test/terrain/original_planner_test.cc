// Tests for src/terrain/original_planner.cc: the original's planner, against paths that its own
// code (systems/PID/PID.py: AStarPlanner.plan, PIDPlanner.smooth_path_bezier, run with numpy and
// scipy) gave on the same grids, and against the closed forms of its obstacle map and transform.
#include "vb/terrain/original_planner.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support/worlds.h"

namespace vb::terrain {
namespace {

OriginalPlannerGrid EmptyGrid(int rows, int cols) {
  OriginalPlannerGrid g;
  g.rows = rows;
  g.cols = cols;
  g.occupied.assign(static_cast<size_t>(rows) * cols, 0);
  return g;
}

using Cells = std::vector<std::pair<int, int>>;

TEST(OriginalPlannerTest, AStarWithUnitDiagonalsTiesAsTheOriginalsHeap) {
  // Every move costs 1, so this 5-cell path is as short as the straight-then-diagonal ones; the
  // heap's (f, row, col) order picks the original's.
  EXPECT_EQ(*OriginalAStar(EmptyGrid(5, 5), 0, 0, 2, 4), (Cells{{0, 0}, {1, 1}, {2, 2}, {2, 3}, {2, 4}}));
  OriginalPlannerGrid g = EmptyGrid(12, 12);
  for (int r = 3; r < 9; ++r) {
    for (int c = 5; c < 7; ++c) g.occupied[static_cast<size_t>(r) * 12 + c] = 1;
  }
  const Cells expected{{6, 1}, {5, 2}, {4, 3}, {3, 4}, {2, 5}, {2, 6}, {3, 7}, {4, 8}, {5, 9}, {5, 10}};
  EXPECT_EQ(*OriginalAStar(g, 6, 1, 5, 10), expected);
  // One Bezier over the whole path: the ends are the path's, the rest is pulled inside.
  const std::vector<std::pair<double, double>> curve = OriginalBezier(expected);
  ASSERT_EQ(curve.size(), 100u);
  EXPECT_DOUBLE_EQ(curve[0].first, 6.0);
  EXPECT_DOUBLE_EQ(curve[0].second, 1.0);
  EXPECT_NEAR(curve[1].first, 5.909090922074523, 1e-12);
  EXPECT_NEAR(curve[1].second, 1.0909090909090917, 1e-12);
  EXPECT_NEAR(curve[50].first, 2.728832877778639, 1e-12);
  EXPECT_NEAR(curve[50].second, 5.545454545454545, 1e-12);
  EXPECT_DOUBLE_EQ(curve[99].first, 5.0);
  EXPECT_DOUBLE_EQ(curve[99].second, 10.0);
  // Walled off: no path.
  for (int r = 0; r < 12; ++r) g.occupied[static_cast<size_t>(r) * 12 + 5] = 1;
  EXPECT_FALSE(OriginalAStar(g, 6, 1, 5, 10).has_value());
}

TEST(OriginalPlannerTest, ObstacleMapAndAddressingUseTheOriginals129mSpan) {
  terrain::TaskSpec task = test::PlaneTask(128.0);
  task.rocks.push_back({0.0, 0.0, 1.0, 0});  // pixel round(64.5) = 64 (half to even), 4 px
  task.trees.push_back({-30.0, 20.0});
  const OriginalPlannerGrid g = MakeOriginalPlannerGrid(task);
  ASSERT_EQ(g.rows, 129);
  EXPECT_DOUBLE_EQ(g.half_x_m, 64.5);
  // the rock marks rows/cols 62..66, inflated by 4: 58..70
  EXPECT_TRUE(g.Occupied(58, 58));
  EXPECT_TRUE(g.Occupied(70, 70));
  EXPECT_FALSE(g.Occupied(57, 64));
  EXPECT_FALSE(g.Occupied(64, 71));
  // the tree at pixel (round(44.5), round(34.5)) = (44, 34), inflated: 40..48 x 30..38
  EXPECT_TRUE(g.Occupied(40, 30));
  EXPECT_FALSE(g.Occupied(39, 34));
  // Positions by truncation: (60, 0) is pixel (int(64.5), int(124.5)) = (64, 124), and the path
  // starts at that pixel's world point (124 - 64.5, 64.5 - 64) = (59.5, 0.5).
  int r = 0, c = 0;
  OriginalPlannerPixel(g, Vec2(60.0, 0.0), &r, &c);
  EXPECT_EQ(r, 64);
  EXPECT_EQ(c, 124);
  const std::optional<std::vector<Vec2>> path = OriginalPlanPath(g, Vec2(60.0, 0.0), Vec2(-60.0, 0.0));
  ASSERT_TRUE(path.has_value());
  ASSERT_EQ(path->size(), 100u);
  EXPECT_DOUBLE_EQ(path->front().x(), 59.5);
  EXPECT_DOUBLE_EQ(path->front().y(), 0.5);
  EXPECT_DOUBLE_EQ(path->back().x(), -64.5 + 4.0);  // pixel int(4.5) = 4
  EXPECT_DOUBLE_EQ(path->back().y(), 0.5);
  // around the inflated rock: somewhere the curve leaves the straight line y = 0.5
  double max_offset = 0.0;
  for (const Vec2& p : *path) max_offset = std::max(max_offset, std::abs(p.y() - 0.5));
  EXPECT_GT(max_offset, 1.0);
}

}  // namespace
}  // namespace vb::terrain
