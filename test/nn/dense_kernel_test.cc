// The batched kernel (dense_kernel.h): the baseline (SSE2) and AVX2 paths give the same bits as
// a plain scalar loop over each sample, for every layer shape and batch size (full vectors,
// register tiles and the left-over samples), and the kernel's exp is within 2 ulp-ish of
// std::exp with the same bits on both paths. On a CPU without AVX2 the path comparison is skipped
// (the scalar comparison still runs).
#include "vb/nn/dense_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "vb/nn/mlp.h"

namespace vb::nn {
namespace {

// The per-sample sequence the kernel promises, in the test's own scalar code (this project is
// compiled with -ffp-contract=off everywhere, so no multiply-add is fused here either).
void Reference(const std::vector<float>& w, const std::vector<float>& b, int in, int out,
               bool relu, const std::vector<float>& x, int xs, std::vector<float>& y, int ys,
               int n) {
  for (int o = 0; o < out; ++o) {
    for (int k = 0; k < n; ++k) {
      float acc = b[o];
      for (int i = 0; i < in; ++i) acc = acc + w[static_cast<size_t>(o) * in + i] * x[static_cast<size_t>(i) * xs + k];
      if (relu) acc = acc > 0.f ? acc : 0.f;
      y[static_cast<size_t>(o) * ys + k] = acc;
    }
  }
}

TEST(DenseKernel, EveryPathEqualsTheScalarLoopBitForBit) {
  std::mt19937 gen(7);
  std::normal_distribution<float> g(0.f, 1.f);
  const bool avx2 = KernelIsaAvailable(KernelIsa::kAvx2);
  std::printf("best path on this CPU: %s\n", KernelIsaName(BestKernelIsa()));
  int checked = 0;
  for (int in : {1, 3, 4, 15, 19, 48}) {
    for (int out : {1, 2, 3, 5, 6, 15, 48}) {
      for (int n : {1, 3, 4, 7, 8, 11, 12, 23, 24, 25, 31, 33, 100, 625}) {
        for (bool relu : {false, true}) {
          const int xs = n + 3, ys = n + 5;   // strides wider than the batch
          std::vector<float> w(static_cast<size_t>(in) * out), b(out), x(static_cast<size_t>(in) * xs);
          for (float& v : w) v = g(gen);
          for (float& v : b) v = g(gen);
          for (float& v : x) v = g(gen) * 3.f;
          std::vector<float> want(static_cast<size_t>(out) * ys, -7.f), base = want, wide = want;
          Reference(w, b, in, out, relu, x, xs, want, ys, n);
          DenseBatch(KernelIsa::kBaseline, w.data(), b.data(), in, out, relu, x.data(), xs,
                     base.data(), ys, n);
          ASSERT_EQ(0, std::memcmp(want.data(), base.data(), want.size() * sizeof(float)))
              << "baseline in " << in << " out " << out << " n " << n;
          if (avx2) {
            DenseBatch(KernelIsa::kAvx2, w.data(), b.data(), in, out, relu, x.data(), xs,
                       wide.data(), ys, n);
            ASSERT_EQ(0, std::memcmp(want.data(), wide.data(), want.size() * sizeof(float)))
                << "avx2 in " << in << " out " << out << " n " << n;
          }
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 6 * 7 * 14 * 2);
  if (!avx2) GTEST_SKIP() << "no AVX2 on this CPU: only the baseline path was compared";
}

TEST(DenseKernel, ExpIsAccurateAndTheSameBitsOnEveryPath) {
  std::vector<float> x;
  for (float v = -87.f; v <= 88.f; v += 0.0137f) x.push_back(v);
  const size_t zero_at = x.size();
  for (float v : {0.f, -0.f, 1.f, -1.f, 1e-8f, -1e-8f}) x.push_back(v);
  x.push_back(-1000.f);
  x.push_back(1000.f);
  x.push_back(-std::numeric_limits<float>::infinity());
  x.push_back(std::numeric_limits<float>::infinity());
  x.push_back(std::numeric_limits<float>::quiet_NaN());
  x.push_back(0.5f);   // odd count: a scalar tail on both paths
  const int n = static_cast<int>(x.size());
  std::vector<float> base(n), wide(n);
  ExpBatch(KernelIsa::kBaseline, x.data(), base.data(), n);
  double worst = 0.0;
  for (int k = 0; k < n; ++k) {
    if (std::isnan(x[k])) {
      EXPECT_TRUE(std::isnan(base[k]));
    } else if (x[k] < -88.f) {
      EXPECT_EQ(base[k], 0.f) << x[k];
    } else if (x[k] > 89.f) {
      EXPECT_EQ(base[k], std::numeric_limits<float>::infinity()) << x[k];
    } else {
      const double want = std::exp(static_cast<double>(x[k]));
      worst = std::max(worst, std::abs(base[k] - want) / want);
    }
  }
  std::printf("max relative error of the kernel's exp on [-87, 88]: %.3g\n", worst);
  EXPECT_LT(worst, 2.5e-7);
  EXPECT_EQ(base[zero_at], 1.f);       // exp(0) = 1 exactly
  EXPECT_EQ(base[zero_at + 1], 1.f);
  if (!KernelIsaAvailable(KernelIsa::kAvx2)) GTEST_SKIP() << "no AVX2 on this CPU";
  ExpBatch(KernelIsa::kAvx2, x.data(), wide.data(), n);
  EXPECT_EQ(0, std::memcmp(base.data(), wide.data(), n * sizeof(float)));
}

}  // namespace
}  // namespace vb::nn
