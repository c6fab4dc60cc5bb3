// Small synthetic worlds for tests: flat or planar ground with uniform material.
#pragma once

#include <algorithm>
#include <functional>
#include <string>

#include "io/vehicle_io.h"
#include "vb/terrain/task.h"

namespace vb::test {

// Sets the heights of `t`, a square world with vertices every 1 m (rows and cols already sized),
// to z = h(x, y) at its vertices, and its height range.
inline void FillHeights(terrain::TaskSpec* t, const std::function<double(double, double)>& h) {
  const int n = t->heights.cols;
  const double half = t->size_x_m / 2;
  double lo = 1e300, hi = -1e300;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const double z = h(-half + c, half - r);
      t->heights.heights_m[static_cast<size_t>(r) * n + c] = z;
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  }
  t->min_height_m = lo;
  t->max_height_m = hi > lo ? hi : lo + 1.0;
}

// A size x size m world (vertices every 1 m) whose surface is z = slope_x * x + slope_y * y,
// all patches of class `surface` with friction `mu`, no obstacles, one pair.
inline terrain::TaskSpec PlaneTask(double size_m = 128.0, double slope_x = 0.0,
                                   double slope_y = 0.0, double mu = 0.9,
                                   terrain::SurfaceClass surface = terrain::SurfaceClass::kConcrete) {
  terrain::TaskSpec t;
  t.name = "plane";
  t.source_file = "<synthetic>";
  t.size_x_m = t.size_y_m = size_m;
  const int n = static_cast<int>(size_m) + 1;
  t.heights.rows = t.heights.cols = n;
  t.heights.heights_m.resize(static_cast<size_t>(n) * n);
  FillHeights(&t, [&](double x, double y) { return slope_x * x + slope_y * y; });
  t.patches.rows = t.patches.cols = 16;
  t.patches.classes.assign(256, surface);
  t.patches.friction.assign(256, terrain::IsDeformable(surface) ? 0.0 : mu);
  terrain::StartGoalPair p;
  p.start_m = Vec2(-20, 0);
  p.goal_m = Vec2(20, 0);
  for (int x = -20; x <= 20; ++x) p.path_m.push_back(Vec2(x, 0));
  t.pairs.push_back(p);
  return t;
}

// A 128 m PlaneTask whose heights are h(x, y) at the 1 m vertices.
inline terrain::TaskSpec WorldOf(const std::function<double(double, double)>& h) {
  terrain::TaskSpec t = PlaneTask(128.0);
  FillHeights(&t, h);
  return t;
}

inline vehicles::VehicleParams Hmmwv() {
  return io::LoadVehicle(std::string(VB_SOURCE_DIR) + "/data/vehicles/hmmwv.yaml");
}

// The same HMMWV with the TMeasy handling tire.
inline vehicles::VehicleParams HmmwvTmeasy() {
  return io::LoadVehicle(std::string(VB_SOURCE_DIR) + "/data/vehicles/hmmwv_tmeasy.yaml");
}

}  // namespace vb::test
