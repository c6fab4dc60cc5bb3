// floor and ceil of a double by truncation: the same integral values as std::floor / std::ceil
// (which are exact), cheaper on baseline x86-64, which has no rounding instruction before SSE4.1
// (GCC emits ~19 instructions for each). A zero's sign may differ from std::floor's (-0.0 vs
// +0.0): use them where the result is converted to an integer, compared, or offset by a nonzero
// amount, none of which sees that sign. |x| >= 2^52 (integral already), infinities and NaN go to
// the library functions.
#pragma once

#include <cmath>
#include <cstdint>

namespace vb {

inline double FloorExact(double x) {
  if (!(std::abs(x) < 4503599627370496.0)) return std::floor(x);
  const double t = static_cast<double>(static_cast<int64_t>(x));
  return t > x ? t - 1.0 : t;
}

inline double CeilExact(double x) {
  if (!(std::abs(x) < 4503599627370496.0)) return std::ceil(x);
  const double t = static_cast<double>(static_cast<int64_t>(x));
  return t < x ? t + 1.0 : t;
}

}  // namespace vb
