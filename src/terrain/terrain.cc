#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_heights.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "vb/engine/error.h"
#include "vb/engine/exact_round.h"

namespace vb::terrain {
namespace {

using detail::CellCoords;
using detail::Locate;
using detail::PlaneHeight;

// Upward unit normal from the grid-coordinate gradient; v grows southward (-y), hence the sign.
inline Vec3 NormalFromGradient(double dh_du, double dh_dv, double dx, double dy) {
  const double gx = dh_du / dx;
  const double gy = -dh_dv / dy;
  const double inv_norm = 1.0 / std::sqrt(gx * gx + gy * gy + 1.0);
  return Vec3(-gx * inv_norm, -gy * inv_norm, inv_norm);
}

}  // namespace

Terrain::Terrain(const TaskSpec& task)
    : grid_(task.heights),
      patches_(task.patches),
      size_x_m_(task.size_x_m),
      size_y_m_(task.size_y_m) {
  VB_DEMAND(grid_.rows >= 2 && grid_.cols >= 2);
  VB_DEMAND(grid_.heights_m.size() == static_cast<size_t>(grid_.rows) * grid_.cols);
  VB_DEMAND(size_x_m_ > 0.0 && size_y_m_ > 0.0);
  VB_DEMAND(patches_.classes.size() == static_cast<size_t>(patches_.rows) * patches_.cols);
  VB_DEMAND(patches_.friction.size() == patches_.classes.size());
  half_x_m_ = 0.5 * size_x_m_;
  half_y_m_ = 0.5 * size_y_m_;
  dx_ = size_x_m_ / (grid_.cols - 1);
  dy_ = size_y_m_ / (grid_.rows - 1);
}

void Heights(const Terrain& terrain, const double* x_m, const double* y_m, int n, double* out) {
  const HeightGrid& grid = terrain.grid();
  const double half_x = 0.5 * terrain.size_x_m(), half_y = 0.5 * terrain.size_y_m();
  const double dx = terrain.spacing_x_m(), dy = terrain.spacing_y_m();
  const double* h = grid.heights_m.data();
  const int cols = grid.cols;
  for (int i = 0; i < n; ++i) {
    const CellCoords p = Locate(grid, half_x, half_y, dx, dy, x_m[i], y_m[i]);
    const double* row0 = h + static_cast<size_t>(p.r) * cols + p.c;
    const double* row1 = row0 + cols;
    // both triangles' planes, as PlaneHeight computes them, then a select
    const double lower = row0[0] + p.fu * (row0[1] - row0[0]) + p.fv * (row1[0] - row0[0]);
    const double upper = row1[1] - (1.0 - p.fu) * (row1[1] - row1[0]) - (1.0 - p.fv) * (row1[1] - row0[1]);
    // select by bit mask: no branch for the predictor to miss (the same value as PlaneHeight's)
    const uint64_t take_lower = -static_cast<uint64_t>(p.fu + p.fv <= 1.0);
    uint64_t lo_bits, up_bits;
    std::memcpy(&lo_bits, &lower, sizeof lower);
    std::memcpy(&up_bits, &upper, sizeof upper);
    const uint64_t bits = (lo_bits & take_lower) | (up_bits & ~take_lower);
    std::memcpy(&out[i], &bits, sizeof bits);
  }
}

Vec3 Terrain::Normal(double x_m, double y_m) const {
  double dh_du, dh_dv;
  PlaneHeight(grid_, Locate(grid_, 0.5 * size_x_m_, 0.5 * size_y_m_, dx_, dy_, x_m, y_m), &dh_du,
              &dh_dv);
  return NormalFromGradient(dh_du, dh_dv, dx_, dy_);
}

void Terrain::PatchIndex(double x_m, double y_m, int* row, int* col) const {
  // patch (i, j) covers x in [-sx/2 + j*sx/cols, -sx/2 + (j+1)*sx/cols), y likewise from the north
  const int j = static_cast<int>(FloorExact((x_m + half_x_m_) * patches_.cols / size_x_m_));
  const int i = static_cast<int>(FloorExact((half_y_m_ - y_m) * patches_.rows / size_y_m_));
  *col = std::min(std::max(j, 0), patches_.cols - 1);
  *row = std::min(std::max(i, 0), patches_.rows - 1);
}

SurfaceClass Terrain::SurfaceAt(double x_m, double y_m) const {
  if (patches_.rows <= 0 || patches_.cols <= 0) return SurfacePoint().surface;
  int i, j;
  PatchIndex(x_m, y_m, &i, &j);
  return patches_.classes[static_cast<size_t>(i) * patches_.cols + j];
}

GroundMix Terrain::MixAround(double x_m, double y_m, double half_m) const {
  if (patches_.rows <= 0 || patches_.cols <= 0) {
    return IsDeformable(SurfacePoint().surface) ? GroundMix::kDeformable : GroundMix::kRigid;
  }
  int i0, j0, i1, j1;
  PatchIndex(x_m - half_m, y_m + half_m, &i0, &j0);  // north-west corner: smallest row and col
  PatchIndex(x_m + half_m, y_m - half_m, &i1, &j1);
  bool rigid = false, deformable = false;
  for (int i = i0; i <= i1; ++i) {
    for (int j = j0; j <= j1; ++j) {
      (IsDeformable(patches_.classes[static_cast<size_t>(i) * patches_.cols + j]) ? deformable
                                                                                   : rigid) = true;
    }
  }
  if (rigid && deformable) return GroundMix::kMixed;
  return deformable ? GroundMix::kDeformable : GroundMix::kRigid;
}

SurfacePoint Terrain::Query(double x_m, double y_m) const {
  SurfacePoint out;
  double dh_du, dh_dv;
  out.height_m = PlaneHeight(
      grid_, Locate(grid_, 0.5 * size_x_m_, 0.5 * size_y_m_, dx_, dy_, x_m, y_m), &dh_du, &dh_dv);
  out.normal_W = NormalFromGradient(dh_du, dh_dv, dx_, dy_);
  // a task without semantics (unit tests, bare height fields) keeps the SurfacePoint defaults
  if (patches_.rows > 0 && patches_.cols > 0) {
    int i, j;
    PatchIndex(x_m, y_m, &i, &j);
    const size_t k = static_cast<size_t>(i) * patches_.cols + j;
    out.surface = patches_.classes[k];
    out.friction = patches_.friction[k];
  }
  return out;
}

void Terrain::Mesh(std::vector<Vec3>* vertices_W, std::vector<int>* triangles) const {
  const int rows = grid_.rows;
  const int cols = grid_.cols;
  vertices_W->clear();
  vertices_W->reserve(static_cast<size_t>(rows) * cols);
  // vertices in the grid's row-major order, at the same coordinates the queries use
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      vertices_W->emplace_back(-0.5 * size_x_m_ + c * dx_, 0.5 * size_y_m_ - r * dy_,
                               grid_.At(r, c));
    }
  }
  triangles->clear();
  triangles->reserve(static_cast<size_t>(rows - 1) * (cols - 1) * 6);
  // two triangles per cell split along SW-NE, both counter-clockwise seen from above
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      const int nw = r * cols + c;
      const int ne = nw + 1;
      const int sw = nw + cols;
      const int se = sw + 1;
      triangles->insert(triangles->end(), {sw, se, ne, sw, ne, nw});
    }
  }
}

}  // namespace vb::terrain
