// Batched dense layer and exp with the samples in the vector lanes (dense_kernel.h).
//
// One template text, instantiated for vectors of W floats with GCC's vector extensions: W = 4 in
// the baseline functions (SSE2, every x86-64 CPU), W = 8 in the functions compiled for AVX2
// (`target("avx2")`, called only when the CPU has it), W = 1 for the samples left over after the
// last full vector. Each lane does the same IEEE single-precision operations in the same order as
// a scalar loop over that sample would, so the width changes the speed and never a bit. This file
// is compiled with -ffp-contract=off (no fused multiply-add; src/nn/CMakeLists.txt), and
// target("avx2") does not enable FMA instructions either.
#include "vb/nn/dense_kernel.h"

#include <cstdlib>
#include <string>

#include "vb/engine/error.h"

namespace vb::nn {

namespace {

#define VB_INLINE inline __attribute__((always_inline))

template <int W>
struct Lanes {
  typedef float V __attribute__((vector_size(4 * W)));
  typedef int VI __attribute__((vector_size(4 * W)));
  // for loads and stores straight from float arrays: no 16/32-byte alignment, may alias floats
  typedef float VM __attribute__((vector_size(4 * W), aligned(4), may_alias));
};

alignas(64) constexpr float kOnes[16] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};

template <int W>
VB_INLINE typename Lanes<W>::V Load(const float* p) {
  return *reinterpret_cast<const typename Lanes<W>::VM*>(p);
}
template <int W>
VB_INLINE void Store(float* p, typename Lanes<W>::V v) {
  *reinterpret_cast<typename Lanes<W>::VM*>(p) = v;
}

// Register tile: KO outputs x KN vectors of W samples, accumulated over all inputs (4 x 2: eight
// accumulators, two inputs and a broadcast weight fit the 16 vector registers without spills).
template <int W, int KO, int KN>
VB_INLINE void Tile(const float* w, const float* b, int in, bool relu, const float* x, int xs,
                    float* y, int ys, int o0, int k0) {
  using V = typename Lanes<W>::V;
  const V zero = {};
  // The bias in every lane as bias x 1 (exact, -0 included), spelled like the weight broadcasts
  // below; the empty asm hides the ones' value, else GCC 12 builds the splat lane by lane through
  // the stack (a store-forwarding stall per tile).
  const float* ones = kOnes;
  asm("" : "+r"(ones));
  const V one = Load<W>(ones);
  V acc[KO][KN];
  for (int o = 0; o < KO; ++o) {
    for (int j = 0; j < KN; ++j) acc[o][j] = b[o0 + o] * one;
  }
  const float* wrow = w + static_cast<long>(o0) * in;
  for (int i = 0; i < in; ++i) {
    V xv[KN];
    const float* xi = x + static_cast<long>(i) * xs + k0;
    for (int j = 0; j < KN; ++j) xv[j] = Load<W>(xi + j * W);
    for (int o = 0; o < KO; ++o) {
      const float s = wrow[static_cast<long>(o) * in + i];   // broadcast to the lanes
      for (int j = 0; j < KN; ++j) acc[o][j] = acc[o][j] + s * xv[j];
    }
  }
  for (int o = 0; o < KO; ++o) {
    float* yo = y + static_cast<long>(o0 + o) * ys + k0;
    for (int j = 0; j < KN; ++j) {
      V v = acc[o][j];
      if (relu) v = v > zero ? v : zero;
      Store<W>(yo + j * W, v);
    }
  }
}

// All outputs for the samples [k0, k0 + KN * W).
template <int W, int KN>
VB_INLINE void Columns(const float* w, const float* b, int in, int out, bool relu, const float* x,
                       int xs, float* y, int ys, int k0) {
  int o0 = 0;
  for (; o0 + 4 <= out; o0 += 4) Tile<W, 4, KN>(w, b, in, relu, x, xs, y, ys, o0, k0);
  for (; o0 < out; ++o0) Tile<W, 1, KN>(w, b, in, relu, x, xs, y, ys, o0, k0);
}

template <int W>
VB_INLINE void Dense(const float* w, const float* b, int in, int out, bool relu, const float* x,
                     int xs, float* y, int ys, int n) {
  int k0 = 0;
  for (; k0 + 2 * W <= n; k0 += 2 * W) Columns<W, 2>(w, b, in, out, relu, x, xs, y, ys, k0);
  for (; k0 + W <= n; k0 += W) Columns<W, 1>(w, b, in, out, relu, x, xs, y, ys, k0);
  for (; k0 < n; ++k0) Columns<1, 1>(w, b, in, out, relu, x, xs, y, ys, k0);
}

// exp on W lanes: Cody-Waite range reduction x = n ln2 + r and a degree-7 polynomial for e^r
// (the classic single-precision Cephes scheme), then the exponent bits of 2^n.
template <int W>
VB_INLINE void ExpLanes(const float* in, float* out) {
  using V = typename Lanes<W>::V;
  using VI = typename Lanes<W>::VI;
  const V x = Load<W>(in);
  const V zero = {};
  const V hi = zero + 88.3762626647949f;
  const V lo = zero - 88.3762626647949f;
  const auto is_nan = x != x;
  V xc = is_nan ? zero : x;
  xc = xc > hi ? hi : xc;
  xc = xc < lo ? lo : xc;
  V fx = xc * 1.44269504088896341f + 0.5f;
  const V t = __builtin_convertvector(__builtin_convertvector(fx, VI), V);   // trunc
  fx = t > fx ? t - 1.0f : t;                                                // floor
  V r = xc - fx * 0.693359375f;
  r = r - fx * -2.12194440e-4f;
  const V z = r * r;
  V p = zero + 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * z + r;
  p = p + 1.0f;
  VI e = __builtin_convertvector(fx, VI) + 127;
  e = e << 23;
  const V pow2n = reinterpret_cast<V>(e);
  V result = p * pow2n;
  const V inf = zero + __builtin_inff();
  result = x > hi ? inf : result;
  result = x < lo ? zero : result;
  result = is_nan ? x : result;
  Store<W>(out, result);
}

template <int W>
VB_INLINE void Exp(const float* in, float* out, int n) {
  int k = 0;
  for (; k + W <= n; k += W) ExpLanes<W>(in + k, out + k);
  for (; k < n; ++k) ExpLanes<1>(in + k, out + k);
}

void DenseBaseline(const float* w, const float* b, int in, int out, bool relu, const float* x,
                   int xs, float* y, int ys, int n) {
  Dense<4>(w, b, in, out, relu, x, xs, y, ys, n);
}

__attribute__((target("avx2"))) void DenseAvx2(const float* w, const float* b, int in, int out,
                                                bool relu, const float* x, int xs, float* y,
                                                int ys, int n) {
  Dense<8>(w, b, in, out, relu, x, xs, y, ys, n);
}

void ExpBaseline(const float* in, float* out, int n) { Exp<4>(in, out, n); }

__attribute__((target("avx2"))) void ExpAvx2(const float* in, float* out, int n) {
  Exp<8>(in, out, n);
}

bool CpuHasAvx2() {
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
}

}  // namespace

bool KernelIsaAvailable(KernelIsa isa) {
  return isa == KernelIsa::kBaseline || (isa == KernelIsa::kAvx2 && CpuHasAvx2());
}

KernelIsa BestKernelIsa() {
  // VB_NN_KERNEL=baseline forces the SSE2 path (to measure what a CPU without AVX2 gets; the
  // results are the same bits either way)
  static const bool forced_baseline = [] {
    const char* v = std::getenv("VB_NN_KERNEL");
    return v != nullptr && std::string(v) == "baseline";
  }();
  return CpuHasAvx2() && !forced_baseline ? KernelIsa::kAvx2 : KernelIsa::kBaseline;
}

const char* KernelIsaName(KernelIsa isa) {
  return isa == KernelIsa::kAvx2 ? "avx2" : "baseline (sse2)";
}

void DenseBatch(KernelIsa isa, const float* w, const float* b, int in, int out, bool relu,
                const float* x, int x_stride, float* y, int y_stride, int n) {
  VB_DEMAND(KernelIsaAvailable(isa));
  if (isa == KernelIsa::kAvx2) {
    DenseAvx2(w, b, in, out, relu, x, x_stride, y, y_stride, n);
  } else {
    DenseBaseline(w, b, in, out, relu, x, x_stride, y, y_stride, n);
  }
}

void ExpBatch(KernelIsa isa, const float* in, float* out, int n) {
  VB_DEMAND(KernelIsaAvailable(isa));
  if (isa == KernelIsa::kAvx2) {
    ExpAvx2(in, out, n);
  } else {
    ExpBaseline(in, out, n);
  }
}

}  // namespace vb::nn
