// FloorExact / CeilExact (vb/engine/exact_round.h) give std::floor's and std::ceil's values.
#include "vb/engine/exact_round.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "support/lcg.h"

namespace vb {
namespace {

TEST(ExactRoundTest, SameValuesAsTheLibrary) {
  test::UniformLcg uniform(99);
  const double special[] = {0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 1.0 - 1e-16, -1.0 + 1e-16,
                            std::nextafter(2.0, 0.0), std::nextafter(-2.0, 0.0), 4503599627370495.5,
                            -4503599627370495.5, 4503599627370496.0, 1e300, -1e300,
                            std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity()};
  for (double x : special) {
    EXPECT_EQ(FloorExact(x), std::floor(x)) << x;
    EXPECT_EQ(CeilExact(x), std::ceil(x)) << x;
  }
  EXPECT_TRUE(std::isnan(FloorExact(std::nan(""))));
  EXPECT_TRUE(std::isnan(CeilExact(std::nan(""))));
  for (int i = 0; i < 200000; ++i) {
    const double scale = std::pow(10.0, -3.0 + 12.0 * uniform());
    const double x = (uniform() - 0.5) * scale;
    ASSERT_EQ(FloorExact(x), std::floor(x)) << x;
    ASSERT_EQ(CeilExact(x), std::ceil(x)) << x;
  }
}

}  // namespace
}  // namespace vb
