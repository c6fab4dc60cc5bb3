#include "vb/terrain/obstacle_field.h"

#include <algorithm>
#include <cmath>

#include <string>

#include "vb/engine/exact_round.h"
#include "vb/terrain/obstacle_shape.h"
#include "vb/terrain/terrain_physics.h"

namespace vb::terrain {

namespace {
constexpr double kEdgeSampleSpacing_m = 0.05;   // at world scale 1
constexpr double kCell_m = 8.0;                 // broadphase cell at world scale 1
}  // namespace

namespace {
// A shape of local points (obstacle_shape.h) placed at (x, y), resting on the ground: its lowest
// point at the lowest terrain height under its outline.
engine::ConvexShape RestingHull(const Terrain& terrain, double x_m, double y_m,
                                const std::vector<Vec3>& local, double spacing,
                                const std::string& what) {
  std::vector<Vec2> outline = Outline(local);
  for (Vec2& p : outline) p += Vec2(x_m, y_m);
  const double base_m = ObstacleBaseHeight(terrain, outline);
  std::vector<Vec3> points = local;
  for (Vec3& p : points) p += Vec3(x_m, y_m, base_m);
  engine::ConvexShape hull = engine::MakeConvexHull(points, spacing, what);
  // Bullet's hull computer rounds its vertices (~1e-4 of the extent): set the lowest one back
  // onto the ground exactly
  Pose lift;
  lift.position = Vec3(0.0, 0.0, base_m - hull.aabb_min.z());
  return hull.Transformed(lift);
}
}  // namespace

ObstacleField::ObstacleField(const TaskSpec& task, const Terrain& terrain) {
  const double spacing = kEdgeSampleSpacing_m * task.scale;
  // Boxes (format v1): bottom face at the lowest terrain point of the square footprint (the
  // original centred rocks on a height read at the wrong place, so they floated or sank by up to
  // ~1 m, reference_verti_bench.md §2.8). Other shapes: their convex hull, lowest point at the
  // lowest terrain point under their outline.
  for (size_t i = 0; i < task.rocks.size(); ++i) {
    const RockSpec& rock = task.rocks[i];
    if (task.rock_shape.kind == ObstacleShapeKind::kBox) {
      const Vec3 half_m = 0.5 * RockBoxSize(task, rock);
      const Vec3 center(rock.x_m, rock.y_m,
                        ObstacleBaseHeight(terrain, rock.x_m, rock.y_m, 2.0 * half_m.x()) +
                            half_m.z());
      obstacles_.push_back({engine::MakeBox(center, half_m, spacing), static_cast<int>(i),
                            kObstacleFriction});
    } else {
      obstacles_.push_back({RestingHull(terrain, rock.x_m, rock.y_m, RockShapePoints(task, rock),
                                        spacing, "obstacles.rocks[" + std::to_string(i) + "]"),
                            static_cast<int>(i), kObstacleFriction});
    }
  }
  const Vec3 tree_half_m = 0.5 * TreeBoxSize(task);
  const std::vector<Vec3> tree_local = TreeShapePoints(task);
  for (size_t j = 0; j < task.trees.size(); ++j) {
    const TreeSpec& tree = task.trees[j];
    if (task.tree_shape.kind == ObstacleShapeKind::kBox) {
      const Vec3 center(tree.x_m, tree.y_m,
                        ObstacleBaseHeight(terrain, tree.x_m, tree.y_m, 2.0 * tree_half_m.x()) +
                            tree_half_m.z());
      obstacles_.push_back({engine::MakeBox(center, tree_half_m, spacing),
                            kTreeTagOffset + static_cast<int>(j), kObstacleFriction});
    } else {
      obstacles_.push_back({RestingHull(terrain, tree.x_m, tree.y_m, tree_local, spacing,
                                        "obstacles.trees[" + std::to_string(j) + "]"),
                            kTreeTagOffset + static_cast<int>(j), kObstacleFriction});
    }
  }
  // Runs of 32 samples with their boxes (ObstacleContacts skips the runs far from a body).
  constexpr int kRun = 32;
  for (Obstacle& o : obstacles_) {
    const int n = static_cast<int>(o.shape.samples.size());
    for (int b = 0; b < n; b += kRun) {
      SampleRun run;
      run.begin = b;
      run.end = std::min(n, b + kRun);
      run.lo = run.hi = o.shape.samples[static_cast<size_t>(b)];
      for (int i = b; i < run.end; ++i) {
        run.lo = run.lo.cwiseMin(o.shape.samples[static_cast<size_t>(i)]);
        run.hi = run.hi.cwiseMax(o.shape.samples[static_cast<size_t>(i)]);
      }
      o.sample_runs.push_back(run);
    }
  }
  // Broadphase grid over the world (obstacles may reach beyond its edge: clamped into it).
  cell_m_ = kCell_m * task.scale;
  x0_ = -0.5 * task.size_x_m;
  y0_ = -0.5 * task.size_y_m;
  cols_ = std::max(1, static_cast<int>(std::ceil(task.size_x_m / cell_m_)));
  rows_ = std::max(1, static_cast<int>(std::ceil(task.size_y_m / cell_m_)));
  cells_.assign(static_cast<size_t>(cols_) * rows_, {});
  for (size_t k = 0; k < obstacles_.size(); ++k) {
    const engine::ConvexShape& s = obstacles_[k].shape;
    const int c0 = std::clamp(static_cast<int>(std::floor((s.aabb_min.x() - x0_) / cell_m_)), 0, cols_ - 1);
    const int c1 = std::clamp(static_cast<int>(std::floor((s.aabb_max.x() - x0_) / cell_m_)), 0, cols_ - 1);
    const int r0 = std::clamp(static_cast<int>(std::floor((s.aabb_min.y() - y0_) / cell_m_)), 0, rows_ - 1);
    const int r1 = std::clamp(static_cast<int>(std::floor((s.aabb_max.y() - y0_) / cell_m_)), 0, rows_ - 1);
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) cells_[static_cast<size_t>(r) * cols_ + c].push_back(static_cast<int>(k));
  }
  stamp_.assign(obstacles_.size(), 0);
}

void ObstacleField::Overlapping(const Vec3& lo, const Vec3& hi, std::vector<int>* out) const {
  out->clear();
  if (obstacles_.empty() || !lo.allFinite() || !hi.allFinite()) return;
  ++query_;
  if (query_ == 0) {  // wrapped: reset the stamps
    std::fill(stamp_.begin(), stamp_.end(), 0);
    query_ = 1;
  }
  const int c0 = std::clamp(static_cast<int>(FloorExact((lo.x() - x0_) / cell_m_)), 0, cols_ - 1);
  const int c1 = std::clamp(static_cast<int>(FloorExact((hi.x() - x0_) / cell_m_)), 0, cols_ - 1);
  const int r0 = std::clamp(static_cast<int>(FloorExact((lo.y() - y0_) / cell_m_)), 0, rows_ - 1);
  const int r1 = std::clamp(static_cast<int>(FloorExact((hi.y() - y0_) / cell_m_)), 0, rows_ - 1);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      for (int k : cells_[static_cast<size_t>(r) * cols_ + c]) {
        if (stamp_[static_cast<size_t>(k)] == query_) continue;
        stamp_[static_cast<size_t>(k)] = query_;
        const engine::ConvexShape& s = obstacles_[static_cast<size_t>(k)].shape;
        if ((s.aabb_min.array() <= hi.array()).all() && (lo.array() <= s.aabb_max.array()).all()) {
          out->push_back(k);
        }
      }
    }
  }
  std::sort(out->begin(), out->end());
}

}  // namespace vb::terrain
