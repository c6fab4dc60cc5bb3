#include "vb/vehicles/track_belt.h"

namespace vb::vehicles {

double BeltLength(const BeltLoop& loop, Vec2* gradient) {
  double length = 0.0;
  for (int i = 0; i < loop.n; ++i) gradient[i].setZero();
  for (int i = 0; i < loop.n; ++i) {
    const int j = (i + 1) % loop.n;
    const Vec2 d = loop.centre[j] - loop.centre[i];
    const double len = d.norm();
    length += len;
    if (len > 1e-12) {
      const Vec2 u = d / len;
      gradient[j] += u;
      gradient[i] -= u;
    }
  }
  return length;
}

}  // namespace vb::vehicles
