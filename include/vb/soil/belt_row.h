// One grid row under a flat belt segment, for the SCM solver's track contact (scm_soil.cc
// TrackContact): which nodes of the row the belt covers, and how much of each node's cell.
//
// The segment runs from a to b; its horizontal projection has the components (sx, sy) and the
// squared length len2; (lx, ly) is the horizontal unit vector across it. Along the grid row
// y = j dx, a node at x = i dx lies at t (0 at a, 1 at b, along the projection) and l (across)
// linear in x:
//   t = t_row + (x - ax) sx / len2,  l = l_row + (x - ax) lx,
// with t_row = (y - ay) sy / len2 and l_row = (y - ay) ly. The node is covered if it is on the
// segment (0 <= t <= t_end; t_end is 1 for the run's last segment and just below 1 for the
// others, so that a node belongs to one segment only) and its cell (+-dx/2 across) overlaps the
// belt's width: it then carries the share of its cell the belt covers,
//   cover = min(1, (half_w - |l|) / cell_w + 0.5) > 0,
// so that the covers of a row across the belt sum to the belt's width over cell_w wherever the
// belt stands between the pressed columns. cell_w is the width of the cell a pressed node stands
// for: dx if the belt presses every node, 2 dx if it presses every second node each way (the
// belt's coarse grid, docs/soil.md).
//
// The solver evaluates this in two places (a tile's first covered node, then each node that may
// touch); both must give the same t, l and cover bit for bit, hence one function.
#pragma once

#include <algorithm>
#include <cmath>

namespace vb::soil {

struct BeltRow {
  double dx = 0.0;        // grid spacing (m)
  double cell_w = 0.0;    // width of a pressed node's cell (m): dx times the belt's node stride
  double ax = 0.0;        // x of the segment's start a (m)
  double sx = 0.0;        // x extent of the segment's horizontal projection (m)
  double len2 = 1.0;      // squared length of the horizontal projection (m^2), > 0
  double lx = 0.0;        // x component of the horizontal unit vector across the segment
  double half_w = 0.0;    // half the belt's width (m)
  double hw_scan = 0.0;   // half_w + cell_w / 2: the farthest a covered node lies across (m)
  double t_end = 1.0;     // last t on the segment
  double t_row = 0.0;     // t at x = ax on this row
  double l_row = 0.0;     // l at x = ax on this row (m)

  // Whether the belt covers node i of the row; if so, its t, l and cover.
  bool Covers(int i, double* t, double* l, double* cover) const {
    const double ux = i * dx - ax;
    *t = t_row + ux * sx / len2;
    *l = l_row + ux * lx;
    if (std::abs(*l) > hw_scan || *t < 0.0 || *t > t_end) return false;
    *cover = std::min(1.0, (half_w - std::abs(*l)) / cell_w + 0.5);
    return *cover > 0.0;
  }
};

}  // namespace vb::soil
