// The wheel's cylinder over the soil grid, for the SCM solver's wheel contact (scm_soil.cc):
// the lowest point of the tread on a node's vertical line, and the cheap bound that lets the
// wheel scan skip a node without that intersection. Both here so that the bound's promise (it
// never skips a node the intersection would press) is tested against the intersection itself
// (test/soil/wheel_bottom_test.cc).
#pragma once

#include <cmath>

#include "vb/engine/types.h"

namespace vb::soil {

// Lowest point of the wheel cylinder (centre c, unit axis a, radius r, half width hw) on the
// vertical line through (x, y); false if the line misses the tread. `lat` is the position
// along the axis.
// Always inlined: a call per scanned node costs more than the test (the wheel scan, the rim).
[[gnu::always_inline]] inline bool WheelBottomAt(const Vec3& c, const Vec3& a, double r,
                                                 double hw, double x, double y, double* z,
                                                 double* lat) {
  const double ux = x - c.x(), uy = y - c.y();
  const double ua = ux * a.x() + uy * a.y();
  const double qa = 1.0 - a.z() * a.z();
  const double qb = -2.0 * a.z() * ua;
  const double qc = ux * ux + uy * uy - ua * ua - r * r;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc <= 0.0 || qa < 1e-6) return false;
  const double t = (-qb - std::sqrt(disc)) / (2.0 * qa);
  *lat = ua + t * a.z();
  *z = c.z() + t;
  return std::abs(*lat) <= hw;
}

// The height bound. A point of the cylinder's surface with |lat| <= hw at horizontal distance
// lon from the axle's vertical plane (lon = offset . fwd, fwd the horizontal rolling direction)
// lies at or above
//   c.z - |a.z| hw - sqrt(1 - a.z^2) sqrt(r^2 - lon^2)
// (its radial part is lon fwd + s u, u = a x fwd with u.z = -sqrt(1 - a.z^2), s^2 = r^2 - lon^2;
// none where |lon| > r). So WheelBottomAt's hit over a node at level L is at or above L when
// d = z_clear - L >= 0 and d^2 >= (1 - a.z^2)(r^2 - lon^2), with z_clear = c.z - |a.z| hw - 1e-6
// (1e-6 m of slack, far above the rounding of the hit and of lon walked along a row).
struct WheelHeightBound {
  double z_clear = 0.0;   // c.z - |a.z| hw - 1e-6 (m)
  double h2 = 0.0;        // 1 - a.z^2
  double r2 = 0.0;        // r^2 (m^2)
  WheelHeightBound(const Vec3& c, const Vec3& a, double r, double hw)
      : z_clear(c.z() - std::abs(a.z()) * hw - 1e-6), h2(1.0 - a.z() * a.z()), r2(r * r) {}
  // True: no point of the tread over a node at `level_m`, `lon_m` from the axle's plane, is
  // below the level, so the node is not pressed and needs no intersection.
  [[gnu::always_inline]] bool Clears(double level_m, double lon_m) const {
    const double d = z_clear - level_m;
    return d >= 0.0 && d * d >= h2 * (r2 - lon_m * lon_m);
  }
};

}  // namespace vb::soil
