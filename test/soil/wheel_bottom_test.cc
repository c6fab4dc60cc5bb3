// The wheel scan's height bound (include/vb/soil/wheel_bottom.h) skips a node without
// intersecting the cylinder when the tread cannot be below the node's level there. The skip is
// exact only if the bound never clears a node the intersection would press (a hit below the
// level, within the tread). Property-tested here against WheelBottomAt itself on random wheel
// poses (cambered and rolled up to |a.z| = 0.6), radii, widths, nodes and levels, with levels
// concentrated near the hit, where the two tests decide differently if at all.
#include "vb/soil/wheel_bottom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace vb::soil {
namespace {

TEST(WheelBottomTest, TheHeightBoundNeverClearsAPressedNode) {
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int cleared = 0, pressed = 0, near_misses = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double r = 0.05 + 0.55 * (0.5 + 0.5 * u(rng));
    const double hw = 0.02 + 0.3 * (0.5 + 0.5 * u(rng));
    const Vec3 c(3.0 * u(rng), 3.0 * u(rng), 0.5 * u(rng));
    const double az = 0.6 * u(rng);
    const double heading = 3.14159 * u(rng);
    const double h = std::sqrt(1.0 - az * az);
    const Vec3 a(h * std::cos(heading), h * std::sin(heading), az);
    Vec3 fwd = a.cross(Vec3::UnitZ());
    fwd.normalize();
    const WheelHeightBound bound(c, a, r, hw);
    for (int k = 0; k < 50; ++k) {
      const double reach = r + hw;
      const double x = c.x() + reach * u(rng), y = c.y() + reach * u(rng);
      double hit_z = 0.0, lat = 0.0;
      const bool over_tread = WheelBottomAt(c, a, r, hw, x, y, &hit_z, &lat);
      // Levels around the hit (or around the wheel's bottom where the line misses the tread).
      const double around = over_tread ? hit_z : c.z() - r;
      const double level = around + (k % 2 == 0 ? 1e-3 : 0.2) * u(rng);
      const double lon = (x - c.x()) * fwd.x() + (y - c.y()) * fwd.y();
      const bool would_press = over_tread && hit_z < level;
      if (bound.Clears(level, lon)) {
        ++cleared;
        ASSERT_FALSE(would_press) << "trial " << trial << " node " << k << ": hit " << hit_z
                                  << " below level " << level;
        if (over_tread && hit_z - level < 1e-3) ++near_misses;
      }
      if (would_press) ++pressed;
    }
  }
  // The property is not vacuous: the bound clears many nodes, some within 1 mm of being pressed,
  // and many nodes are pressed.
  std::printf("cleared %d (within 1 mm of pressed: %d), pressed %d of 200000 nodes\n", cleared,
              near_misses, pressed);
  EXPECT_GT(cleared, 20000);
  EXPECT_GT(near_misses, 100);
  EXPECT_GT(pressed, 10000);
}

}  // namespace
}  // namespace vb::soil
