// Obstacle shapes (obstacle_shape.h): boulders and trunks have the original's box dimensions,
// rest on the terrain (lowest point on the surface, nowhere above it, buried no deeper than the
// ground rises under the outline), and occupy the occupancy cells of their projection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/worlds.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/obstacle_field.h"
#include "vb/terrain/obstacle_shape.h"
#include "vb/terrain/terrain_physics.h"

namespace vb::terrain {
namespace {

// A rugged 64 m world: a plane of slope (0.15, -0.08) plus a 1.2 m bump field, rocks and trees
// of the benchmark's family.
TaskSpec RuggedTask(ObstacleShapeKind rock_kind, ObstacleShapeKind tree_kind) {
  TaskSpec t = test::PlaneTask(64.0);
  double lo = 1e300, hi = -1e300;
  for (int r = 0; r < t.heights.rows; ++r) {
    for (int c = 0; c < t.heights.cols; ++c) {
      const double x = -32.0 + c, y = 32.0 - r;
      const double h = 0.15 * x - 0.08 * y + 1.2 * std::sin(0.31 * x) * std::cos(0.23 * y);
      t.heights.heights_m[static_cast<size_t>(r) * t.heights.cols + c] = h;
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
  }
  t.min_height_m = lo;
  t.max_height_m = hi;
  t.generator_seed = 17;
  for (int i = 0; i < 12; ++i) {
    t.rocks.push_back({-25.0 + 4.3 * i, 20.0 - 3.7 * i, 0.7 + 0.5 * (i % 5) / 4.0});
  }
  for (int j = 0; j < 4; ++j) t.trees.push_back({-20.0 + 11.3 * j, -15.0 + 2.1 * j});
  t.rock_shape.kind = rock_kind;
  t.tree_shape.kind = tree_kind;
  AssignShapeSeeds(&t);
  return t;
}

TEST(ObstacleShapeTest, BoulderFitsTheOriginalsBoxAndDependsOnItsSeed) {
  const Vec3 box(4.4, 4.4, 3.8);
  const std::vector<Vec3> a = BoulderPoints(1, box), b = BoulderPoints(2, box);
  for (const std::vector<Vec3>* p : {&a, &b}) {
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    for (const Vec3& q : *p) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    EXPECT_NEAR(hi.x() - lo.x(), 4.4, 1e-9);
    EXPECT_NEAR(hi.y() - lo.y(), 4.4, 1e-9);
    EXPECT_NEAR(lo.z(), 0.0, 1e-12);
    EXPECT_NEAR(hi.z(), 3.8, 1e-9);
    EXPECT_NEAR(lo.x() + hi.x(), 0.0, 1e-9);
    EXPECT_NEAR(lo.y() + hi.y(), 0.0, 1e-9);
    // a dome: the outline is rounder than the box (area between the inscribed octagon's and the
    // box's), and the top is narrower than the base
    const double area = PolygonArea(Outline(*p));
    EXPECT_GT(area, 0.6 * 4.4 * 4.4);
    EXPECT_LT(area, 0.9 * 4.4 * 4.4);
  }
  EXPECT_NE(a, b);
  EXPECT_EQ(a, BoulderPoints(1, box));   // deterministic
  // the hull's size (docs/benchmarks.md: contact cost against boxes)
  int vertices = 0, faces = 0;
  size_t samples = 0;
  for (uint64_t seed = 0; seed < 20; ++seed) {
    const engine::ConvexShape hull = engine::MakeConvexHull(BoulderPoints(seed, box), 0.05, "b");
    vertices += static_cast<int>(hull.vertices.size());
    faces += static_cast<int>(hull.faces.size());
    samples += hull.samples.size();
  }
  std::printf("boulder hulls (20 seeds, scale 1): %.1f vertices, %.1f faces, %.0f edge samples "
              "(a box: 8, 6, %zu)\n",
              vertices / 20.0, faces / 20.0, samples / 20.0,
              engine::MakeBox(Vec3::Zero(), 0.5 * box, 0.05).samples.size());
  EXPECT_LE(faces / 20, 60);
}

TEST(ObstacleShapeTest, TrunkIsATwelveSidedPrismOfTheTreeBox) {
  TaskSpec t = RuggedTask(ObstacleShapeKind::kBoulder, ObstacleShapeKind::kTrunk);
  const std::vector<Vec3> p = TreeShapePoints(t);
  ASSERT_EQ(p.size(), 24u);
  const std::vector<Vec2> outline = Outline(p);
  EXPECT_EQ(outline.size(), 12u);
  // regular 12-gon of circumradius 0.5 m: area 3 r^2
  EXPECT_NEAR(PolygonArea(outline), 3.0 * 0.25, 1e-9);
  double top = 0.0;
  for (const Vec3& q : p) top = std::max(top, q.z());
  EXPECT_DOUBLE_EQ(top, 5.0);
}

// Lowest hull point on the surface (within 2 mm), no part of the bottom above the ground (the
// ground is nowhere lower than the lowest point inside the outline), burial at most the ground's
// rise under the outline.
TEST(ObstacleShapeTest, EveryShapeRestsOnTheTerrain) {
  for (ObstacleShapeKind kind : {ObstacleShapeKind::kBoulder, ObstacleShapeKind::kBox}) {
    const TaskSpec t = RuggedTask(kind, kind == ObstacleShapeKind::kBox ? kind
                                                                         : ObstacleShapeKind::kTrunk);
    const Terrain ground(t);
    const ObstacleField field(t, ground);
    ASSERT_EQ(field.obstacles().size(), t.rocks.size() + t.trees.size());
    double worst_burial = 0.0, worst_rise = 0.0;
    for (size_t k = 0; k < field.obstacles().size(); ++k) {
      const engine::ConvexShape& s = field.obstacles()[k].shape;
      const bool rock = k < t.rocks.size();
      const Vec2 at = rock ? Vec2(t.rocks[k].x_m, t.rocks[k].y_m)
                           : Vec2(t.trees[k - t.rocks.size()].x_m,
                                  t.trees[k - t.rocks.size()].y_m);
      std::vector<Vec2> outline =
          Outline(rock ? RockShapePoints(t, t.rocks[k]) : TreeShapePoints(t));
      for (Vec2& q : outline) q += at;
      // sample the ground densely (5 cm) over the outline
      double g_lo = 1e300, g_hi = -1e300;
      const Vec2 lo(s.aabb_min.x(), s.aabb_min.y()), hi(s.aabb_max.x(), s.aabb_max.y());
      for (double x = lo.x(); x <= hi.x(); x += 0.05) {
        for (double y = lo.y(); y <= hi.y(); y += 0.05) {
          if (!InsideConvexPolygon(outline, Vec2(x, y))) continue;
          const double h = ground.Height(x, y);
          g_lo = std::min(g_lo, h);
          g_hi = std::max(g_hi, h);
        }
      }
      for (size_t e = 0; e < outline.size(); ++e) {   // and the boundary, every 5 mm
        const Vec2 a = outline[e], b = outline[(e + 1) % outline.size()];
        const int n = static_cast<int>(std::ceil((b - a).norm() / 0.005));
        for (int i = 0; i <= n; ++i) {
          const Vec2 q = a + (b - a) * (static_cast<double>(i) / n);
          g_lo = std::min(g_lo, ground.Height(q.x(), q.y()));
          g_hi = std::max(g_hi, ground.Height(q.x(), q.y()));
        }
      }
      const double bottom = s.aabb_min.z();
      // lowest point on the surface: at the ground's lowest point under the outline
      EXPECT_NEAR(bottom, g_lo, 0.002) << k;
      // no float: the bottom is nowhere above the ground (beyond 1 mm: ObstacleBaseHeight walks
      // the outline every 1/32 of the grid spacing, here 3 cm)
      EXPECT_LE(bottom, g_lo + 1e-3) << k;
      worst_burial = std::max(worst_burial, g_hi - bottom);
      worst_rise = std::max(worst_rise, g_hi - g_lo);
      EXPECT_LE(g_hi - bottom, (g_hi - g_lo) + 0.01) << k;
      // the hull's height is the box's (up to the hull computer's rounding, 1e-4 of the extent)
      const double height = rock ? RockBoxSize(t, t.rocks[k]).z() : TreeBoxSize(t).z();
      EXPECT_NEAR(s.aabb_max.z() - bottom, height, 1e-3) << k;
    }
    std::printf("%s: deepest burial %.3f m (= the ground's rise under the outline, at most "
                "%.3f m)\n",
                std::string(ObstacleShapeKindName(kind)).c_str(), worst_burial, worst_rise);
  }
}

TEST(ObstacleShapeTest, BaseHeightOverAPolygonOnAPlaneIsItsLowestCorner) {
  TaskSpec t = test::PlaneTask(32.0, 0.2, 0.1);
  const Terrain ground(t);
  const std::vector<Vec2> tri = {{1.3, 0.2}, {4.1, 1.7}, {2.0, 3.9}};
  // lowest at the vertex with the smallest 0.2 x + 0.1 y: (1.3, 0.2) -> 0.28
  EXPECT_NEAR(ObstacleBaseHeight(ground, tri), 0.28, 1e-9);
}

// The occupied cells are those whose centres lie in the outline (plus the obstacle's own cell):
// their area matches the outline's within the cells along its perimeter.
TEST(ObstacleShapeTest, OccupancyFootprintIsTheProjection) {
  const TaskSpec t = RuggedTask(ObstacleShapeKind::kBoulder, ObstacleShapeKind::kTrunk);
  for (size_t i = 0; i < t.rocks.size(); ++i) {
    TaskSpec one = t;
    one.rocks = {t.rocks[i]};
    one.trees.clear();
    const OccupancyGrid g = RasterizeObstacles(one);
    std::vector<Vec2> outline = Outline(RockShapePoints(t, t.rocks[i]));
    double perimeter = 0.0;
    for (size_t k = 0; k < outline.size(); ++k) {
      perimeter += (outline[(k + 1) % outline.size()] - outline[k]).norm();
    }
    const Vec2 at(t.rocks[i].x_m, t.rocks[i].y_m);
    for (Vec2& q : outline) q += at;
    int cells = 0;
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c) {
        const bool inside = InsideConvexPolygon(outline, g.CenterOf({r, c}));
        const bool own = g.CellOf(at) == Cell{r, c};
        EXPECT_EQ(g.Occupied(r, c), inside || own) << i << " " << r << " " << c;
        cells += g.Occupied(r, c);
      }
    }
    const double area = PolygonArea(outline);
    EXPECT_NEAR(cells * g.cell_m * g.cell_m, area, 0.5 * perimeter * g.cell_m) << i;
  }
  // a trunk (1 m across) occupies its own cell
  TaskSpec tree = t;
  tree.rocks.clear();
  tree.trees = {{3.2, -4.4}};
  const OccupancyGrid g = RasterizeObstacles(tree);
  EXPECT_TRUE(g.Occupied(g.CellOf(Vec2(3.2, -4.4)).row, g.CellOf(Vec2(3.2, -4.4)).col));
}

TEST(ObstacleShapeTest, ShapeSeedsFollowTheTaskNotThePosition) {
  TaskSpec a = RuggedTask(ObstacleShapeKind::kBoulder, ObstacleShapeKind::kTrunk);
  TaskSpec b = a;
  b.generator_seed = 18;
  AssignShapeSeeds(&b);
  EXPECT_NE(a.rocks[0].shape_seed, b.rocks[0].shape_seed);
  EXPECT_NE(a.rocks[0].shape_seed, a.rocks[1].shape_seed);
  TaskSpec c = a;
  AssignShapeSeeds(&c);
  EXPECT_EQ(a.rocks[3].shape_seed, c.rocks[3].shape_seed);
}

}  // namespace
}  // namespace vb::terrain
