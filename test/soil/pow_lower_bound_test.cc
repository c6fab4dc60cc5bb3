// The table lower bound on z^n that lets the SCM solver skip pow in its Bekker yield test: it
// must never exceed std::pow (else a yielding node would be taken as elastic and results would
// change), and it should be tight enough to decide most tests.
#include "vb/soil/pow_lower_bound.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vb::soil {
namespace {

TEST(PowLowerBoundTest, NeverAbovePowAndWithinTheBinFactor) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> log_z(std::log(1e-11), std::log(200.0));
  for (double n : {0.5, 0.793, 1.0, 1.1, 1.3, 2.0}) {   // the benchmark's soils: 0.793, 1.1
    PowLowerBound bound;
    bound.Init(n);
    for (int k = 0; k < 200000; ++k) {
      const double z = std::exp(log_z(rng));
      const double p = std::pow(z, n);
      const double lo = bound(z);
      ASSERT_LE(lo, p) << "n " << n << " z " << z;
      ASSERT_GE(lo, p * std::pow(1.0 + 1.0 / 256.0, -n) * (1.0 - 1e-9)) << "n " << n << " z " << z;
    }
    // the bin edges themselves (z^n exactly at the table points)
    for (int e = -40; e < 8; ++e) {
      for (int b = 0; b < 256; ++b) {
        const double z = std::ldexp(1.0 + b / 256.0, e);
        ASSERT_LE(bound(z), std::pow(z, n)) << "n " << n << " z " << z;
      }
    }
  }
}

TEST(PowLowerBoundTest, NoBoundOutsideItsRange) {
  PowLowerBound bound;
  bound.Init(1.1);
  for (double z : {0.0, -0.0, -0.01, 1e-13, 300.0, 5e-324, static_cast<double>(INFINITY), std::nan("")}) {
    EXPECT_TRUE(std::isnan(bound(z))) << z;
  }
  PowLowerBound off;
  off.Init(-1.0);
  EXPECT_TRUE(std::isnan(off(0.01)));
  PowLowerBound unset;
  EXPECT_TRUE(std::isnan(unset(0.01)));
}

}  // namespace
}  // namespace vb::soil
