// Ziggurat normal sampler: moments and tail probabilities of 10^6 draws against N(0, 1) within
// sampling tolerances, determinism, and the tail beyond the base layer being reached.
#include "vb/engine/normal_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vb {
namespace {

TEST(NormalSamplerTest, MomentsAndTailsMatchTheStandardNormal) {
  Rng rng(12345);
  const int n = 1000000;
  double sum = 0, sum2 = 0, sum3 = 0, sum4 = 0;
  int above1 = 0, above2 = 0, above3 = 0, beyond_r = 0;
  for (int i = 0; i < n; ++i) {
    const double x = NormalSampler::Draw(&rng);
    sum += x;
    sum2 += x * x;
    sum3 += x * x * x;
    sum4 += x * x * x * x;
    above1 += std::abs(x) > 1.0;
    above2 += std::abs(x) > 2.0;
    above3 += std::abs(x) > 3.0;
    beyond_r += std::abs(x) > 3.442619855899;
  }
  // standard errors: mean 1e-3, variance 1.4e-3, skewness 2.4e-3, kurtosis 4.9e-3 (x 5 below)
  EXPECT_NEAR(sum / n, 0.0, 5e-3);
  EXPECT_NEAR(sum2 / n, 1.0, 7e-3);
  EXPECT_NEAR(sum3 / n, 0.0, 1.2e-2);
  EXPECT_NEAR(sum4 / n, 3.0, 2.5e-2);
  // P(|x| > 1) = 0.317311, > 2: 0.0455003, > 3: 0.0026998, > r: 0.000576 (5 standard errors)
  EXPECT_NEAR(above1 / double(n), 0.317311, 5 * std::sqrt(0.317311 * 0.682689 / n));
  EXPECT_NEAR(above2 / double(n), 0.0455003, 5 * std::sqrt(0.0455003 / n));
  EXPECT_NEAR(above3 / double(n), 0.0026998, 5 * std::sqrt(0.0026998 / n));
  EXPECT_NEAR(beyond_r / double(n), 0.000576, 5 * std::sqrt(0.000576 / n));
}

TEST(NormalSamplerTest, SameSeedSameStream) {
  Rng a(7), b(7), c(8);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double x = NormalSampler::Draw(&a);
    EXPECT_EQ(x, NormalSampler::Draw(&b));
    differs |= x != NormalSampler::Draw(&c);
  }
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace vb
