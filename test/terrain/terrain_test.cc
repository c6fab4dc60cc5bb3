// Tests for src/terrain/terrain.cc: the triangulated surface against analytic surfaces.
#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_heights.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "vb/engine/rng.h"

namespace vb::terrain {
namespace {

// A task whose height vertices sample f on a rows x cols grid spanning size_x x size_y, with
// 4 x 4 patches whose class and friction encode the patch index.
TaskSpec SampledTask(int rows, int cols, double size_x, double size_y,
                     const std::function<double(double, double)>& f) {
  TaskSpec t;
  t.size_x_m = size_x;
  t.size_y_m = size_y;
  t.heights.rows = rows;
  t.heights.cols = cols;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double x = -size_x / 2 + c * size_x / (cols - 1);
      const double y = size_y / 2 - r * size_y / (rows - 1);
      t.heights.heights_m.push_back(f(x, y));
    }
  }
  t.patches.rows = 4;
  t.patches.cols = 4;
  for (int k = 0; k < 16; ++k) {
    t.patches.classes.push_back(static_cast<SurfaceClass>(k % 7));
    t.patches.friction.push_back(0.1 + 0.05 * k);
  }
  return t;
}

double PlaneZ(double x, double y) { return 0.3 * x - 0.17 * y + 2.5; }
double Paraboloid(double x, double y) { return 0.01 * x * x + 0.02 * y * y - 0.005 * x * y; }

TEST(TerrainTest, ReproducesPlaneExactlyAtRandomPoints) {
  // non-square cells and spacing that is not a power of two
  const Terrain terrain(SampledTask(13, 21, 30.0, 18.0, PlaneZ));
  Rng rng(7);
  for (int i = 0; i < 10000; ++i) {
    const double x = rng.Uniform(-15.0, 15.0);
    const double y = rng.Uniform(-9.0, 9.0);
    EXPECT_NEAR(terrain.Height(x, y), PlaneZ(x, y), 1e-12);
  }
}

TEST(TerrainTest, BatchedHeightsEqualHeightBitForBit) {
  // a rough surface, points inside, outside (clamped), on vertices and diagonals, and a NaN
  const Terrain terrain(SampledTask(17, 23, 30.0, 18.0, [](double x, double y) {
    return Paraboloid(x, y) + 0.3 * std::sin(3.1 * x) * std::cos(2.3 * y);
  }));
  Rng rng(11);
  std::vector<double> x, y;
  for (int i = 0; i < 5000; ++i) {
    x.push_back(rng.Uniform(-20.0, 20.0));
    y.push_back(rng.Uniform(-12.0, 12.0));
  }
  for (int c = 0; c < 23; ++c) {
    x.push_back(-15.0 + c * 30.0 / 22);
    y.push_back(9.0 - c * 18.0 / 16 * 0.5);
  }
  x.push_back(std::nan(""));
  y.push_back(1.0);
  std::vector<double> batch(x.size());
  Heights(terrain, x.data(), y.data(), static_cast<int>(x.size()), batch.data());
  for (size_t i = 0; i < x.size(); ++i) {
    const double one = terrain.Height(x[i], y[i]);
    ASSERT_EQ(0, std::memcmp(&one, &batch[i], sizeof(double))) << "point " << i << " (" << x[i] << ", " << y[i] << ")";
  }
}

TEST(TerrainTest, NormalOfPlane) {
  const Terrain terrain(SampledTask(13, 21, 30.0, 18.0, PlaneZ));
  const Vec3 expected = Vec3(-0.3, 0.17, 1.0).normalized();
  Rng rng(8);
  for (int i = 0; i < 1000; ++i) {
    const double x = rng.Uniform(-15.0, 15.0);
    const double y = rng.Uniform(-9.0, 9.0);
    EXPECT_LT((terrain.Normal(x, y) - expected).norm(), 1e-12);
    const SurfacePoint p = terrain.Query(x, y);
    EXPECT_LT((p.normal_W - expected).norm(), 1e-12);
    EXPECT_NEAR(p.height_m, PlaneZ(x, y), 1e-12);
  }
}

TEST(TerrainTest, ParaboloidMatchedAtVertices) {
  const TaskSpec task = SampledTask(17, 17, 32.0, 32.0, Paraboloid);
  const Terrain terrain(task);
  for (int r = 0; r < 17; ++r) {
    for (int c = 0; c < 17; ++c) {
      const double x = -16.0 + 2.0 * c;
      const double y = 16.0 - 2.0 * r;
      EXPECT_NEAR(terrain.Height(x, y), Paraboloid(x, y), 1e-12) << r << " " << c;
    }
  }
}

TEST(TerrainTest, ContinuousAcrossCellEdgesAndDiagonals) {
  const Terrain terrain(SampledTask(17, 17, 32.0, 32.0, Paraboloid));
  constexpr double kEps = 1e-9;
  Rng rng(9);
  for (int i = 0; i < 2000; ++i) {
    const int c = rng.UniformInt(0, 15);
    const int r = rng.UniformInt(0, 15);
    const double t = rng.Uniform();
    const double x0 = -16.0 + 2.0 * c;
    const double y0 = 16.0 - 2.0 * r;
    // vertical cell edge x = x0 + 2, horizontal edge y = y0 - 2, and the SW-NE diagonal
    const double ye = y0 - 2.0 * t;
    EXPECT_NEAR(terrain.Height(x0 + 2.0 - kEps, ye), terrain.Height(x0 + 2.0 + kEps, ye), 1e-8);
    const double xe = x0 + 2.0 * t;
    EXPECT_NEAR(terrain.Height(xe, y0 - 2.0 + kEps), terrain.Height(xe, y0 - 2.0 - kEps), 1e-8);
    const double xd = x0 + 2.0 * t;
    const double yd = y0 - 2.0 * (1.0 - t);  // on the diagonal from SW (x0, y0-2) to NE (x0+2, y0)
    EXPECT_NEAR(terrain.Height(xd - kEps, yd - kEps), terrain.Height(xd + kEps, yd + kEps), 1e-8);
  }
}

TEST(TerrainTest, SplitsAlongSouthWestNorthEastDiagonal) {
  // one cell with only the NW vertex raised: the raised vertex belongs to triangle (SW, NE, NW)
  // only, so the SE half is flat at 0 and the NW half slopes
  TaskSpec task = SampledTask(2, 2, 1.0, 1.0, [](double, double) { return 0.0; });
  task.heights.heights_m[0] = 1.0;  // NW at (-0.5, 0.5)
  const Terrain terrain(task);
  EXPECT_DOUBLE_EQ(terrain.Height(0.25, -0.25), 0.0);   // SE half
  EXPECT_DOUBLE_EQ(terrain.Height(-0.25, 0.25), 0.5);   // NW half: fu = fv = 0.25
  EXPECT_DOUBLE_EQ(terrain.Height(0.0, 0.0), 0.0);      // on the diagonal
}

TEST(TerrainTest, ClampsOutsideTheGrid) {
  const Terrain terrain(SampledTask(13, 21, 30.0, 18.0, PlaneZ));
  EXPECT_NEAR(terrain.Height(100.0, 3.0), PlaneZ(15.0, 3.0), 1e-12);
  EXPECT_NEAR(terrain.Height(-100.0, -50.0), PlaneZ(-15.0, -9.0), 1e-12);
  EXPECT_NEAR(terrain.Height(2.0, 50.0), PlaneZ(2.0, 9.0), 1e-12);
  int row = -1, col = -1;
  terrain.PatchIndex(100.0, 100.0, &row, &col);
  EXPECT_EQ(row, 0);
  EXPECT_EQ(col, 3);
  terrain.PatchIndex(-100.0, -100.0, &row, &col);
  EXPECT_EQ(row, 3);
  EXPECT_EQ(col, 0);
}

TEST(TerrainTest, PatchLookupAtPatchCorners) {
  // 32 m x 32 m, 4 x 4 patches of 8 m: patch (i, j) spans x in [-16 + 8j, -8 + 8j)
  const Terrain terrain(SampledTask(33, 33, 32.0, 32.0, PlaneZ));
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double x_west = -16.0 + 8.0 * j;
      const double y_north = 16.0 - 8.0 * i;
      int row = -1, col = -1;
      // the north-west corner belongs to the patch; just inside the other corners as well
      terrain.PatchIndex(x_west, y_north, &row, &col);
      EXPECT_EQ(row, i);
      EXPECT_EQ(col, j);
      terrain.PatchIndex(x_west + 8.0 - 1e-9, y_north - 8.0 + 1e-9, &row, &col);
      EXPECT_EQ(row, i);
      EXPECT_EQ(col, j);
      const SurfacePoint p = terrain.Query(x_west + 4.0, y_north - 4.0);
      EXPECT_EQ(p.surface, static_cast<SurfaceClass>((4 * i + j) % 7));
      EXPECT_DOUBLE_EQ(p.friction, 0.1 + 0.05 * (4 * i + j));
    }
  }
}

TEST(TerrainTest, MeshMatchesHeightAtTriangleCentroidsAndFacesUp) {
  const Terrain terrain(SampledTask(9, 12, 22.0, 16.0, Paraboloid));
  std::vector<Vec3> vertices;
  std::vector<int> triangles;
  terrain.Mesh(&vertices, &triangles);
  ASSERT_EQ(vertices.size(), 9u * 12u);
  ASSERT_EQ(triangles.size(), 8u * 11u * 6u);
  for (size_t t = 0; t < triangles.size(); t += 3) {
    const Vec3& a = vertices[triangles[t]];
    const Vec3& b = vertices[triangles[t + 1]];
    const Vec3& c = vertices[triangles[t + 2]];
    const Vec3 centroid = (a + b + c) / 3.0;
    EXPECT_NEAR(terrain.Height(centroid.x(), centroid.y()), centroid.z(), 1e-12);
    // counter-clockwise from above: the face normal points up and equals Normal()
    const Vec3 n = (b - a).cross(c - a).normalized();
    EXPECT_GT(n.z(), 0.0);
    EXPECT_LT((n - terrain.Normal(centroid.x(), centroid.y())).norm(), 1e-12);
  }
}

TEST(TerrainTest, DefaultsWithoutPatches) {
  TaskSpec task = SampledTask(3, 3, 2.0, 2.0, PlaneZ);
  task.patches = PatchGrid();
  const SurfacePoint p = Terrain(task).Query(0.1, 0.2);
  EXPECT_EQ(p.surface, SurfacePoint().surface);
  EXPECT_DOUBLE_EQ(p.friction, SurfacePoint().friction);
}

}  // namespace
}  // namespace vb::terrain
