// vb's body contact generation (terrain/body_contact.h) on hand-made cases with known answers:
// a box resting on a plane, a terrain peak poking into a box's bottom, a box pressed into a rock,
// a wheel against a rock's edge and on its top face; plus the convex hull builder.
#include "vb/terrain/body_contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "support/lcg.h"
#include "support/worlds.h"
#include "vb/engine/convex_shape.h"
#include "vb/engine/error.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb::terrain {
namespace {

engine::ConvexShape Box(const Vec3& center, const Vec3& half, double spacing = 0.25) {
  return engine::MakeBox(center, half, spacing);
}

TEST(ConvexShapeTest, BoxAndHullAgree) {
  const engine::ConvexShape box = Box(Vec3(1, 2, 3), Vec3(0.5, 1.0, 1.5), 0.5);
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.faces.size(), 6u);
  EXPECT_EQ(box.edges.size(), 12u);
  std::vector<Vec3> points = box.vertices;
  points.push_back(Vec3(1, 2, 3));  // an inner point is not a vertex of the hull
  const engine::ConvexShape hull = engine::MakeConvexHull(points, 0.5, "test");
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.faces.size(), 6u);   // coplanar triangles merged
  EXPECT_EQ(hull.edges.size(), 12u);  // no diagonals
  for (const Vec3& p : {Vec3(1, 2, 3), Vec3(1.4, 2.9, 4.4), Vec3(2, 2, 3), Vec3(1, 2, 5)}) {
    EXPECT_NEAR(hull.SignedDistance(p, nullptr), box.SignedDistance(p, nullptr), 1e-12);
  }
  EXPECT_NEAR(box.SignedDistance(Vec3(1, 2, 3), nullptr), -0.5, 1e-12);  // nearest face x
  EXPECT_NEAR(box.SignedDistance(Vec3(1, 2, 5), nullptr), 0.5, 1e-12);
  // samples: 8 vertices + per edge ceil(len / 0.5) - 1 inner points
  EXPECT_EQ(box.samples.size(), 8u + 4 * (1 + 3 + 5));
  EXPECT_THROW(engine::MakeConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)},
                                      0.5, "flat"),
               InputError);
}

// Inside is SignedDistance < 0, bit for bit (value and face), on a grid of points in and around
// a rock-like hull, its vertices and its face planes (the contact queries rely on it).
TEST(ConvexShapeTest, InsideAgreesWithSignedDistanceBitForBit) {
  std::vector<Vec3> points;
  for (int i = 0; i < 24; ++i) {   // a lumpy hull: points on an ellipsoid, radius varied
    const double u = 0.7 * i, v = 1.3 * i + 0.4;
    const double rr = 1.0 + 0.15 * std::sin(3.0 * u);
    points.push_back(Vec3(1.2 * rr * std::cos(u) * std::sin(v), 0.9 * rr * std::sin(u) * std::sin(v),
                          0.7 * rr * std::cos(v)));
  }
  const engine::ConvexShape hull = engine::MakeConvexHull(points, 0.3, "rock");
  std::vector<Vec3> probes = hull.vertices;
  for (const engine::ConvexShape::Face& f : hull.faces) probes.push_back(f.normal * f.offset);
  for (int x = -15; x <= 15; ++x)
    for (int y = -12; y <= 12; ++y)
      for (int z = -10; z <= 10; ++z) probes.push_back(Vec3(0.1 * x, 0.1 * y, 0.1 * z));
  int inside = 0, hint = -1;
  for (const Vec3& p : probes) {
    int face_sd = -1, face_in = -1, face_hinted = -1;
    const double sd = hull.SignedDistance(p, &face_sd);
    double d = 7.0, d_hinted = 7.0;
    const bool in = hull.Inside(p, &d, &face_in);
    // with a hint carried from the previous probe (what the contact loops do)
    const bool in_hinted = hull.Inside(p, &d_hinted, &face_hinted, &hint);
    ASSERT_EQ(in, sd < 0.0) << p.transpose();
    ASSERT_EQ(in_hinted, in) << p.transpose();
    if (in) {
      ++inside;
      EXPECT_EQ(d, sd);
      EXPECT_EQ(face_in, face_sd);
      EXPECT_EQ(d_hinted, sd);
      EXPECT_EQ(face_hinted, face_sd);
    }
  }
  EXPECT_GT(inside, 1000);                              // the test saw both kinds of point
  EXPECT_LT(inside, static_cast<int>(probes.size()) - 1000);
}

TEST(BodyContactTest, BoxSunkIntoAPlaneTouchesAtItsBottom) {
  const TaskSpec task = test::PlaneTask(32.0);  // z = 0, concrete mu 0.9
  const Terrain ground(task);
  // 2 x 1 x 0.5 m box whose bottom is 1 cm below the ground
  const engine::ConvexShape box = Box(Vec3(0.3, 0.2, 0.24), Vec3(1.0, 0.5, 0.25));
  ContactScratch scratch;
  std::vector<BodyContact> out;
  GroundContacts(box, ground, 0.8, 8, &scratch, &out);
  ASSERT_EQ(out.size(), 8u);  // more candidates (bottom samples), the best-spread 8 kept
  double x_lo = 1e9, x_hi = -1e9;
  for (const BodyContact& c : out) {
    EXPECT_NEAR(c.depth_m, 0.01, 1e-12);
    EXPECT_NEAR(c.point_W.z(), -0.01, 1e-12);
    EXPECT_EQ(c.normal_W, Vec3::UnitZ());
    EXPECT_DOUBLE_EQ(c.friction, 0.8);  // min(body 0.8, concrete 0.9)
    EXPECT_EQ(c.obstacle_tag, -1);
    x_lo = std::min(x_lo, c.point_W.x());
    x_hi = std::max(x_hi, c.point_W.x());
  }
  EXPECT_DOUBLE_EQ(x_lo, -0.7);  // the corners are among them
  EXPECT_DOUBLE_EQ(x_hi, 1.3);
  // lifted 2 cm: nothing
  out.clear();
  GroundContacts(Box(Vec3(0.3, 0.2, 0.27), Vec3(1.0, 0.5, 0.25)), ground, 0.8, 8, &scratch, &out);
  EXPECT_TRUE(out.empty());
}

TEST(BodyContactTest, TerrainPeakInsideTheBoxPushesItUpAlongTheBottomFace) {
  TaskSpec task = test::PlaneTask(32.0);
  // one grid vertex 0.5 m up at (0, 0): a pyramid peak between the box's bottom samples
  task.heights.heights_m[static_cast<size_t>(16) * 33 + 16] = 0.5;
  const Terrain ground(task);
  const engine::ConvexShape box = Box(Vec3(0.0, 0.0, 0.7), Vec3(1.5, 0.9, 0.25));  // bottom 0.45
  ContactScratch scratch;
  std::vector<BodyContact> out;
  GroundContacts(box, ground, 0.8, 8, &scratch, &out);
  ASSERT_FALSE(out.empty());
  double deepest = 0.0;
  for (const BodyContact& c : out) {
    EXPECT_NEAR(c.normal_W.z(), 1.0, 1e-12);
    deepest = std::max(deepest, c.depth_m);
  }
  EXPECT_NEAR(deepest, 0.05, 1e-12);  // the peak 5 cm above the bottom face
}

TEST(BodyContactTest, BoxPressedIntoARockTopIsPushedUp) {
  TaskSpec task = test::PlaneTask(64.0);
  task.rocks.push_back({0.0, 0.0, 1.0});  // 4.4 x 4.4 x 3.8 box on flat ground: top at 3.8
  const Terrain ground(task);
  const ObstacleField field(task, ground);
  ASSERT_EQ(field.obstacles().size(), 1u);
  EXPECT_NEAR(field.obstacles()[0].shape.aabb_max.z(), 3.8, 1e-12);
  const engine::ConvexShape box = Box(Vec3(1.0, 0.5, 4.03), Vec3(0.5, 0.5, 0.25));  // 2 cm in
  ContactScratch scratch;
  std::vector<BodyContact> out;
  ObstacleContacts(box, field, 0.8, 8, &scratch, &out);
  ASSERT_FALSE(out.empty());
  for (const BodyContact& c : out) {
    EXPECT_NEAR(c.depth_m, 0.02, 1e-12);
    EXPECT_NEAR(c.normal_W.z(), 1.0, 1e-12);
    EXPECT_EQ(c.obstacle_tag, 0);
    EXPECT_DOUBLE_EQ(c.friction, 0.8);
  }
  // far away: the broadphase reports nothing
  out.clear();
  ObstacleContacts(Box(Vec3(20.0, 0.0, 1.0), Vec3(0.5, 0.5, 0.5)), field, 0.8, 8, &scratch, &out);
  EXPECT_TRUE(out.empty());
}

TEST(BodyContactTest, WheelAtARockEdgeIsPushedTowardsItsCentre) {
  TaskSpec task = test::PlaneTask(64.0);
  task.rocks.push_back({0.0, 0.0, 0.1});  // 0.44 x 0.44 x 0.38 m: a low block, west face x -0.22
  const Terrain ground(task);
  const ObstacleField field(task, ground);
  const double r = 0.467;
  // wheel (axis y) rolling east onto the block's top west edge (x -0.22, z 0.38): its centre
  // 0.3 m west of the edge and 0.25 m above it, 3.2 cm inside the tread
  const Vec3 center(-0.52, 0.0, 0.63);
  ContactScratch scratch;
  std::vector<BodyContact> out;
  WheelObstacleContacts(center, Vec3::UnitY(), r, 0.127, field, 0.9, 4, &scratch, &out);
  ASSERT_FALSE(out.empty());
  const Vec3 edge(-0.22, 0.0, 0.38);
  const Vec3 expected_normal = (center - edge).normalized();  // up and back: the wheel climbs
  bool found = false;
  for (const BodyContact& c : out) {
    EXPECT_GT(c.normal_W.z(), 0.5);
    EXPECT_LT(c.normal_W.x(), 0.0);
    if (std::abs(c.point_W.y()) < 0.03) {
      EXPECT_NEAR(c.normal_W.dot(expected_normal), 1.0, 1e-3);
      EXPECT_NEAR(c.depth_m, r - (center - edge).norm(), 2e-3);
      found = true;
    }
  }
  EXPECT_TRUE(found);
  EXPECT_DOUBLE_EQ(out[0].friction, 0.8);  // min(tire 0.9, rock 0.8)
}

TEST(BodyContactTest, WheelStandingOnARockTopIsPushedUp) {
  TaskSpec task = test::PlaneTask(64.0);
  task.rocks.push_back({0.0, 0.0, 1.0});  // top face at z 3.8
  const Terrain ground(task);
  const ObstacleField field(task, ground);
  ContactScratch scratch;
  std::vector<BodyContact> out;
  WheelObstacleContacts(Vec3(0.5, 0.3, 3.8 + 0.46), Vec3::UnitY(), 0.467, 0.127, field, 0.9, 4,
                        &scratch, &out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].normal_W, Vec3::UnitZ());
  EXPECT_NEAR(out[0].depth_m, 0.007, 1e-12);
  EXPECT_NEAR(out[0].point_W.z(), 3.8 - 0.007, 1e-12);
}

TEST(BodyContactTest, ReductionKeepsTheDeepestAndSpreadsTheRest) {
  std::vector<BodyContact> c(5);
  const double xs[5] = {0.0, 0.1, 1.0, 2.0, 2.1};
  for (int i = 0; i < 5; ++i) {
    c[i].point_W = Vec3(xs[i], 0, 0);
    c[i].depth_m = 0.01;
  }
  c[2].depth_m = 0.05;
  std::vector<char> taken;
  std::vector<BodyContact> out;
  ReduceContacts(c, 3, &taken, &out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].point_W.x(), 1.0);  // deepest
  EXPECT_EQ(out[1].point_W.x(), 2.1);  // then the farthest from it
  EXPECT_EQ(out[2].point_W.x(), 0.0);  // then the farthest from both
}

// A 32 m world of random vertex heights in [0, 0.6) m, for the property tests below.
Terrain RoughGround(test::UniformLcg& uniform) {
  TaskSpec task = test::PlaneTask(32.0);
  for (double& h : task.heights.heights_m) h = 0.6 * uniform();
  return Terrain(task);
}

// A random pose over the middle of that world: x, y in [-8, 8) m, z in [z0, z0 + dz) m, tilted by
// up to 0.3 rad about x and y, any heading.
// Two contact lists equal bit for bit (points, normals, depths), friction and tags included.
void ExpectBitIdentical(const std::vector<BodyContact>& a, const std::vector<BodyContact>& b,
                        int pose) {
  ASSERT_EQ(a.size(), b.size()) << "pose " << pose;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(a[i].point_W.data(), b[i].point_W.data(), 3 * sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(a[i].normal_W.data(), b[i].normal_W.data(), 3 * sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a[i].depth_m, &b[i].depth_m, sizeof(double)), 0);
    EXPECT_EQ(a[i].friction, b[i].friction);
    EXPECT_EQ(a[i].obstacle_tag, b[i].obstacle_tag);
  }
}

Pose RandomPose(test::UniformLcg& uniform, double z0, double dz) {
  Pose pose;
  pose.position = Vec3(-8.0 + 16.0 * uniform(), -8.0 + 16.0 * uniform(), z0 + dz * uniform());
  pose.rotation = Quat(Eigen::AngleAxisd(0.6 * (uniform() - 0.5), Vec3::UnitX())) *
                  Quat(Eigen::AngleAxisd(0.6 * (uniform() - 0.5), Vec3::UnitY())) *
                  Quat(Eigen::AngleAxisd(6.3 * uniform(), Vec3::UnitZ()));
  return pose;
}

// The quick reject used before GroundContacts (GroundBeyondLowestFace) must never hide a contact:
// over a rough ground (random vertex heights) and random tilted box poses near it, whenever it
// says "beyond", GroundContacts finds nothing; and it does pass the common case of a box tilted
// with the slope under it, which the AABB test (MaxGroundHeightUnder) cannot.
TEST(BodyContactTest, LowestFaceRejectNeverHidesAContact) {
  test::UniformLcg uniform(12345);
  const Terrain ground = RoughGround(uniform);
  ContactScratch scratch;
  std::vector<BodyContact> out;
  int rejected = 0, touching = 0;
  for (int k = 0; k < 4000; ++k) {
    const Pose pose = RandomPose(uniform, 0.2, 1.2);
    const engine::ConvexShape local = Box(Vec3::Zero(), Vec3(1.2, 0.6, 0.2));
    const engine::ConvexShape box = local.Transformed(pose);
    out.clear();
    GroundContacts(box, ground, 0.8, 64, &scratch, &out);
    if (!out.empty()) ++touching;
    if (GroundBeyondLowestFace(box, ground)) {
      ++rejected;
      EXPECT_TRUE(out.empty()) << "pose " << k;
    }
  }
  EXPECT_GT(touching, 400);   // the poses do exercise contacts
  EXPECT_GT(rejected, 500);   // and the reject does fire
  // a box tilted 20 deg with a 20 deg slope, 5 cm above it: the AABB test cannot reject it
  const TaskSpec slope = test::PlaneTask(32.0, std::tan(20.0 * M_PI / 180.0));
  const Terrain sloped(slope);
  Pose tilted;
  tilted.rotation = Quat(Eigen::AngleAxisd(-20.0 * M_PI / 180.0, Vec3::UnitY()));
  tilted.position = Vec3(0.0, 0.0, 0.25 / std::cos(20.0 * M_PI / 180.0));  // bottom 5 cm up
  const engine::ConvexShape on_slope = Box(Vec3::Zero(), Vec3(1.2, 0.6, 0.2)).Transformed(tilted);
  EXPECT_LT(on_slope.aabb_min.z(),
            MaxGroundHeightUnder(on_slope.aabb_min, on_slope.aabb_max, sloped));
  EXPECT_TRUE(GroundBeyondLowestFace(on_slope, sloped));
  out.clear();
  GroundContacts(on_slope, sloped, 0.8, 64, &scratch, &out);
  EXPECT_TRUE(out.empty());
  // off the grid: no claim
  Pose off;
  off.position = Vec3(15.5, 0.0, 2.0);
  EXPECT_FALSE(GroundBeyondLowestFace(Box(Vec3::Zero(), Vec3(1.2, 0.6, 0.2)).Transformed(off),
                                      ground));
}

// GroundContacts with the samples posed on the way (only those below the highest ground vertex)
// must find exactly what posing them all first finds: the same contacts, bit for bit.
TEST(BodyContactTest, LazilyPosedSamplesGiveBitIdenticalContacts) {
  test::UniformLcg uniform(777);
  const Terrain ground = RoughGround(uniform);
  const engine::ConvexShape local =
      engine::MakeConvexHull({Vec3(2.1, 0.75, 0.0), Vec3(2.1, -0.75, 0.0), Vec3(2.3, 0.75, 0.44),
                              Vec3(2.3, -0.75, 0.44), Vec3(2.3, 0.75, 0.55), Vec3(2.3, -0.75, 0.55),
                              Vec3(-2.3, 0.75, 0.0), Vec3(-2.3, -0.75, 0.0), Vec3(-2.3, 0.75, 0.55),
                              Vec3(-2.3, -0.75, 0.55)},
                             0.25, "belly");
  ContactScratch scratch;
  std::vector<BodyContact> all, lazy;
  engine::ConvexShape posed, posed_without_samples;
  int touching = 0;
  for (int k = 0; k < 3000; ++k) {
    const Pose pose = RandomPose(uniform, 0.1, 0.8);
    local.TransformInto(pose, &posed);
    local.TransformInto(pose, &posed_without_samples, /*with_samples=*/false);
    const double max_h = MaxGroundHeightUnder(posed.aabb_min, posed.aabb_max, ground);
    all.clear();
    lazy.clear();
    GroundContacts(posed, ground, max_h, 0.8, 8, &scratch, &all);
    GroundContacts(posed_without_samples, local.samples, pose, ground, max_h, 0.8, 8, &scratch,
                   &lazy);
    if (!all.empty()) ++touching;
    ExpectBitIdentical(all, lazy, k);
    // the height alone, as the lazy path computes it, is the posed sample's height bit for bit
    const Mat3 r = pose.rotation.toRotationMatrix();
    for (size_t i = 0; i < local.samples.size(); ++i) {
      const double z = (pose.position + r * local.samples[i]).z();
      EXPECT_EQ(std::memcmp(&z, &posed.samples[i].z(), sizeof(double)), 0) << k << " " << i;
    }
  }
  EXPECT_GT(touching, 300);  // the poses do exercise contacts
}

// The obstacle query with the body's samples posed lazily (only those near an obstacle's box)
// and the obstacles' samples skipped by runs gives the contacts of posing every sample first
// and testing every obstacle sample, bit for bit, in the same order: boulders of several sizes
// and a trunk, a chassis-like piece at 4000 random poses around and into them.
TEST(BodyContactTest, LazilyPosedSamplesAndSampleRunsGiveBitIdenticalObstacleContacts) {
  test::UniformLcg uniform(4242);
  TaskSpec task = test::PlaneTask(64.0);
  task.generator_seed = 11;
  for (int i = 0; i < 9; ++i)
    task.rocks.push_back({-6.0 + 6.0 * (i % 3), -6.0 + 6.0 * (i / 3), 0.4 + 0.2 * i});
  task.trees.push_back({3.0, 3.0});
  task.rock_shape.kind = ObstacleShapeKind::kBoulder;
  AssignShapeSeeds(&task);
  const Terrain ground(task);
  const ObstacleField field(task, ground);
  for (const Obstacle& o : field.obstacles()) {  // the runs cover the samples in order
    int next = 0;
    for (const SampleRun& run : o.sample_runs) {
      ASSERT_EQ(run.begin, next);
      next = run.end;
    }
    ASSERT_EQ(next, static_cast<int>(o.shape.samples.size()));
  }
  const engine::ConvexShape local =
      engine::MakeConvexHull({Vec3(2.1, 0.75, 0.0), Vec3(2.1, -0.75, 0.0), Vec3(2.3, 0.75, 0.44),
                              Vec3(2.3, -0.75, 0.44), Vec3(2.3, 0.75, 0.55), Vec3(2.3, -0.75, 0.55),
                              Vec3(-2.3, 0.75, 0.0), Vec3(-2.3, -0.75, 0.0), Vec3(-2.3, 0.75, 0.55),
                              Vec3(-2.3, -0.75, 0.55)},
                             0.05, "belly");
  // the reference: every obstacle sample tested (runs of one sample skip nothing the per-sample
  // test keeps), every body sample posed (below)
  ObstacleField whole = field;
  for (size_t i = 0; i < whole.obstacles().size(); ++i) {
    auto& o = const_cast<Obstacle&>(whole.obstacles()[i]);  // a test's own copy
    o.sample_runs.clear();
    for (int q = 0; q < static_cast<int>(o.shape.samples.size()); ++q)
      o.sample_runs.push_back({o.shape.samples[static_cast<size_t>(q)],
                               o.shape.samples[static_cast<size_t>(q)], q, q + 1});
  }
  ContactScratch scratch;
  std::vector<BodyContact> all, lazy;
  engine::ConvexShape posed, posed_without_samples;
  int touching = 0;
  for (int k = 0; k < 4000; ++k) {
    const Pose pose = RandomPose(uniform, 0.0, 1.5);
    local.TransformInto(pose, &posed);
    local.TransformInto(pose, &posed_without_samples, /*with_samples=*/false);
    all.clear();
    lazy.clear();
    ObstacleContacts(posed, whole, 0.8, 8, &scratch, &all);
    ObstacleContacts(posed_without_samples, local.samples, pose, field, 0.8, 8, &scratch, &lazy);
    if (!all.empty()) ++touching;
    ExpectBitIdentical(all, lazy, k);
  }
  EXPECT_GT(touching, 400);  // the poses do exercise contacts
}

}  // namespace
}  // namespace vb::terrain
