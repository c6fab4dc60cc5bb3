#include "vb/terrain/obstacle_shape.h"

#include <algorithm>
#include <cmath>

#include "vb/engine/error.h"
#include "vb/engine/rng.h"
#include "vb/terrain/terrain_physics.h"

namespace vb::terrain {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Boulder family parameters (docs/generator.md "Obstacle shapes").
constexpr int kBoulderDirections = 30;     // near-uniform sample directions on the sphere
constexpr int kBoulderRing = 10;           // points on the cut (the boulder's base outline)
constexpr double kBoulderCut = -0.3;       // cut plane height on the unit sphere (below equator)
constexpr int kBoulderBumps = 4;           // seeded bumps and dents
constexpr double kBoulderBumpAmplitude = 0.18;   // of the radius, each bump at most
constexpr double kBoulderJitter = 0.05;          // of the radius, per point
constexpr int kTrunkSides = 12;

double Cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Stretches the points so that their bounding box is box_m, x and y centred on 0, z from 0.
void FitToBox(const Vec3& box_m, std::vector<Vec3>* points) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : *points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 size = hi - lo;
  VB_DEMAND((size.array() > 0.0).all());
  for (Vec3& p : *points) {
    p = Vec3((p.x() - 0.5 * (lo.x() + hi.x())) / size.x() * box_m.x(),
             (p.y() - 0.5 * (lo.y() + hi.y())) / size.y() * box_m.y(),
             (p.z() - lo.z()) / size.z() * box_m.z());
  }
}

}  // namespace

std::string_view ObstacleShapeKindName(ObstacleShapeKind kind) {
  switch (kind) {
    case ObstacleShapeKind::kBox: return "box";
    case ObstacleShapeKind::kBoulder: return "boulder";
    case ObstacleShapeKind::kTrunk: return "trunk";
    case ObstacleShapeKind::kMesh: return "mesh";
  }
  return "unknown";
}

bool ParseObstacleShapeKind(std::string_view name, ObstacleShapeKind* kind) {
  for (ObstacleShapeKind k : {ObstacleShapeKind::kBox, ObstacleShapeKind::kBoulder,
                              ObstacleShapeKind::kTrunk, ObstacleShapeKind::kMesh}) {
    if (name == ObstacleShapeKindName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

void AssignShapeSeeds(TaskSpec* task) {
  for (size_t i = 0; i < task->rocks.size(); ++i) {
    // two SplitMix64 steps over (generator seed, index): unrelated seeds for neighbouring rocks
    Rng mix(task->generator_seed ^ (0xB0D1DE5ull * (static_cast<uint64_t>(i) + 1)));
    mix.NextU64();
    task->rocks[i].shape_seed = mix.NextU64();
  }
}

std::vector<Vec3> BoulderPoints(uint64_t seed, const Vec3& box_m) {
  Rng rng(seed);
  Vec3 bump_dir[kBoulderBumps];
  double bump_amp[kBoulderBumps];
  for (int k = 0; k < kBoulderBumps; ++k) {
    const double z = rng.Uniform(-1.0, 1.0), phi = rng.Uniform(0.0, 2.0 * kPi);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    bump_dir[k] = Vec3(s * std::cos(phi), s * std::sin(phi), z);
    bump_amp[k] = rng.Uniform(-kBoulderBumpAmplitude, kBoulderBumpAmplitude);
  }
  const double turn = rng.Uniform(0.0, 2.0 * kPi);
  auto radius = [&](const Vec3& d) {
    double r = 1.0 + rng.Uniform(-kBoulderJitter, kBoulderJitter);
    for (int k = 0; k < kBoulderBumps; ++k) {
      r += bump_amp[k] * std::exp(-3.0 * (1.0 - d.dot(bump_dir[k])));
    }
    return r;
  };
  std::vector<Vec3> points;
  // Fibonacci directions (golden-angle spiral), turned by a seeded angle; those above the cut
  constexpr double kGolden = 2.39996322972865332;
  for (int i = 0; i < kBoulderDirections; ++i) {
    const double z = 1.0 - (i + 0.5) * 2.0 / kBoulderDirections;
    if (z <= kBoulderCut + 0.1) continue;   // the ring covers the base
    const double s = std::sqrt(1.0 - z * z), phi = turn + kGolden * i;
    const Vec3 d(s * std::cos(phi), s * std::sin(phi), z);
    points.push_back(radius(d) * d);
  }
  // the base: the bumpy sphere's section at the cut
  const double ring_s = std::sqrt(1.0 - kBoulderCut * kBoulderCut);
  for (int j = 0; j < kBoulderRing; ++j) {
    const double phi = turn + 2.0 * kPi * (j + 0.5) / kBoulderRing;
    const Vec3 d(ring_s * std::cos(phi), ring_s * std::sin(phi), kBoulderCut);
    const Vec3 p = radius(d) * d;
    points.emplace_back(p.x(), p.y(), kBoulderCut);
  }
  FitToBox(box_m, &points);
  return points;
}

std::vector<Vec3> PrismPoints(int sides, double diameter_m, double height_m) {
  VB_DEMAND(sides >= 3);
  std::vector<Vec3> points;
  for (double z : {0.0, height_m}) {
    for (int k = 0; k < sides; ++k) {
      const double phi = 2.0 * kPi * k / sides;
      points.emplace_back(0.5 * diameter_m * std::cos(phi), 0.5 * diameter_m * std::sin(phi), z);
    }
  }
  return points;
}

std::vector<Vec3> BoxPoints(const Vec3& box_m) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) {
    points.emplace_back((i & 1) ? 0.5 * box_m.x() : -0.5 * box_m.x(),
                        (i & 2) ? 0.5 * box_m.y() : -0.5 * box_m.y(), (i & 4) ? box_m.z() : 0.0);
  }
  return points;
}

namespace {
std::vector<Vec3> MeshPoints(const ObstacleShapeSpec& shape, double factor) {
  std::vector<Vec3> points = shape.mesh_vertices_m;
  VB_DEMAND(!points.empty());
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 shift(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), lo.z());
  for (Vec3& p : points) p = (p - shift) * factor;
  return points;
}
}  // namespace

std::vector<Vec3> RockShapePoints(const TaskSpec& task, const RockSpec& rock) {
  const Vec3 box = RockBoxSize(task, rock);
  switch (task.rock_shape.kind) {
    case ObstacleShapeKind::kBoulder: return BoulderPoints(rock.shape_seed, box);
    case ObstacleShapeKind::kTrunk: return PrismPoints(kTrunkSides, box.x(), box.z());
    case ObstacleShapeKind::kMesh: return MeshPoints(task.rock_shape, rock.scale * task.scale);
    case ObstacleShapeKind::kBox: break;
  }
  return BoxPoints(box);
}

std::vector<Vec3> TreeShapePoints(const TaskSpec& task) {
  const Vec3 box = TreeBoxSize(task);
  switch (task.tree_shape.kind) {
    case ObstacleShapeKind::kTrunk: return PrismPoints(kTrunkSides, box.x(), box.z());
    case ObstacleShapeKind::kBoulder: return BoulderPoints(0, box);
    case ObstacleShapeKind::kMesh: return MeshPoints(task.tree_shape, task.scale);
    case ObstacleShapeKind::kBox: break;
  }
  return BoxPoints(box);
}

std::vector<Vec2> Outline(const std::vector<Vec3>& points) {
  // Andrew's monotone chain
  std::vector<Vec2> p;
  p.reserve(points.size());
  for (const Vec3& q : points) p.emplace_back(q.x(), q.y());
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && Cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0.0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

bool InsideConvexPolygon(const std::vector<Vec2>& poly, const Vec2& p, double tol_m) {
  const size_t n = poly.size();
  if (n < 3) return false;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % n];
    const double len = (b - a).norm();
    if (Cross(a, b, p) < -tol_m * len) return false;
  }
  return true;
}

double PolygonArea(const std::vector<Vec2>& poly) {
  double a = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

}  // namespace vb::terrain
