// The covered-node test of the SCM track contact (belt_row.h): which grid nodes of a row a flat
// belt segment covers and what share of each cell, against the segment's geometry.
#include "vb/soil/belt_row.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vb::soil {
namespace {

constexpr double kDx = 0.05;

// A row of the grid under the horizontal segment from (ax, ay) to (bx, by), belt half width hw.
// stride: the belt presses every stride-th node each way, each standing for a cell stride dx wide.
BeltRow RowFor(double ax, double ay, double bx, double by, double hw, int j, double t_end,
               int stride = 1) {
  BeltRow row;
  const double sx = bx - ax, sy = by - ay;
  row.dx = kDx;
  row.cell_w = stride * kDx;
  row.ax = ax;
  row.sx = sx;
  row.len2 = sx * sx + sy * sy;
  const double len = std::sqrt(row.len2);
  row.lx = -sy / len;
  const double ly = sx / len;
  row.half_w = hw;
  row.hw_scan = hw + 0.5 * row.cell_w;
  row.t_end = t_end;
  const double uy = j * kDx - ay;
  row.t_row = uy * sy / row.len2;
  row.l_row = uy * ly;
  return row;
}

// Across a belt that crosses the row at right angles, the covers add up to the belt's width in
// cells wherever the belt stands between the grid columns (the effective width is the belt's).
TEST(BeltRowTest, CoversAcrossTheBeltSumToItsWidth) {
  const double hw = 0.19;   // the M113 shoe: 0.38 m
  for (double offset = 0.0; offset < kDx; offset += kDx / 17.0) {
    // the segment runs along y through x = offset, so a grid row crosses it at right angles
    const BeltRow row = RowFor(offset, -1.0, offset, 1.0, hw, 3, 1.0);
    double sum = 0.0;
    int covered = 0;
    for (int i = -20; i <= 20; ++i) {
      double t = 0.0, l = 0.0, cover = 0.0;
      if (!row.Covers(i, &t, &l, &cover)) continue;
      ++covered;
      EXPECT_GT(cover, 0.0);
      EXPECT_LE(cover, 1.0);
      EXPECT_LE(std::abs(l), row.hw_scan);
      EXPECT_NEAR(t, (3 * kDx + 1.0) / 2.0, 1e-12);   // y = 0.15 on a segment from -1 to 1
      sum += cover;
    }
    EXPECT_NEAR(sum * kDx, 2.0 * hw, 1e-12) << "offset " << offset;
    EXPECT_GE(covered, 8);   // 0.38 m over 0.05 m cells: 8 or 9 nodes
    EXPECT_LE(covered, 9);
  }
}

// The belt's coarse grid (every second node each way, each carrying a cell 2 dx wide): the
// covers of the pressed nodes across the belt still add up to its width.
TEST(BeltRowTest, CoarseCoversAcrossTheBeltSumToItsWidth) {
  const double hw = 0.19;
  for (double offset = 0.0; offset < 2.0 * kDx; offset += kDx / 13.0) {
    const BeltRow row = RowFor(offset, -1.0, offset, 1.0, hw, 4, 1.0, 2);
    double sum = 0.0;
    int covered = 0;
    for (int i = -20; i <= 20; i += 2) {
      double t = 0.0, l = 0.0, cover = 0.0;
      if (!row.Covers(i, &t, &l, &cover)) continue;
      ++covered;
      EXPECT_GT(cover, 0.0);
      EXPECT_LE(cover, 1.0);
      EXPECT_LE(std::abs(l), row.hw_scan);
      sum += cover;
    }
    EXPECT_NEAR(sum * 2.0 * kDx, 2.0 * hw, 1e-12) << "offset " << offset;
    EXPECT_GE(covered, 4);   // 0.38 m over 0.1 m cells: 4 or 5 nodes
    EXPECT_LE(covered, 5);
  }
}

// On a diagonal segment: t and l agree with the projection of the node onto the segment, and a
// node is covered exactly when it lies on the segment and within the half width plus half a
// cell across it.
TEST(BeltRowTest, AgreesWithTheSegmentGeometryOnADiagonal) {
  const double ax = 0.31, ay = -0.27, bx = 1.02, by = 0.44, hw = 0.19;
  const double sx = bx - ax, sy = by - ay, len = std::hypot(sx, sy);
  const double t_end = 1.0 - 1e-12;
  int covered = 0, rejected = 0;
  for (int j = -20; j <= 20; ++j) {
    const BeltRow row = RowFor(ax, ay, bx, by, hw, j, t_end);
    for (int i = -20; i <= 40; ++i) {
      const double ux = i * kDx - ax, uy = j * kDx - ay;
      const double t_ref = (ux * sx + uy * sy) / (len * len);
      const double l_ref = (-ux * sy + uy * sx) / len;
      double t = 0.0, l = 0.0, cover = 0.0;
      const bool c = row.Covers(i, &t, &l, &cover);
      EXPECT_NEAR(t, t_ref, 1e-12);
      EXPECT_NEAR(l, l_ref, 1e-12);
      // away from the edges (rounding), the reference decides the same
      const bool inside = t_ref >= 0.0 && t_ref <= t_end && std::abs(l_ref) < hw + 0.5 * kDx;
      const bool near_edge = std::abs(t_ref) < 1e-9 || std::abs(t_ref - t_end) < 1e-9 ||
                             std::abs(std::abs(l_ref) - (hw + 0.5 * kDx)) < 1e-9;
      if (!near_edge) {
        EXPECT_EQ(c, inside) << "i " << i << " j " << j;
      }
      if (c) {
        ++covered;
        EXPECT_NEAR(cover, std::min(1.0, (hw - std::abs(l_ref)) / kDx + 0.5), 1e-9);
      } else {
        ++rejected;
      }
    }
  }
  // 1.0 m of segment x 0.43 m of scanned width over 0.05 m cells: ~170 nodes
  EXPECT_GT(covered, 150);
  EXPECT_LT(covered, 190);
  EXPECT_GT(rejected, 0);
}

// The segment's ends: t < 0 and t > t_end are not covered (a node belongs to one segment only).
TEST(BeltRowTest, EndsBelongToOneSegment) {
  // along x from 0 to 1 m; row j = 0 runs along the segment's centre line
  const BeltRow inner = RowFor(0.0, 0.0, 1.0, 0.0, 0.19, 0, 1.0 - 1e-12);
  const BeltRow last = RowFor(0.0, 0.0, 1.0, 0.0, 0.19, 0, 1.0);
  double t = 0.0, l = 0.0, cover = 0.0;
  EXPECT_FALSE(inner.Covers(-1, &t, &l, &cover));   // x = -0.05: before a
  EXPECT_TRUE(inner.Covers(0, &t, &l, &cover));     // x = 0: a itself
  EXPECT_DOUBLE_EQ(cover, 1.0);
  EXPECT_FALSE(inner.Covers(20, &t, &l, &cover));   // x = 1: b belongs to the next segment
  EXPECT_TRUE(last.Covers(20, &t, &l, &cover));     // ... unless this is the last one
  EXPECT_DOUBLE_EQ(t, 1.0);
  EXPECT_FALSE(last.Covers(21, &t, &l, &cover));
}

}  // namespace
}  // namespace vb::soil
