// The batched dense layer behind Mlp::ForwardBatch: y = act(W x + b) for n samples at once, with
// the samples in the vector lanes (feature-major data: x[i * x_stride + k] is input i of sample
// k). Every sample gets the same scalar sequence of float operations whatever the vector width
// (acc = b_o; acc = acc + w_oi * x_ik for i = 0, 1, ...; separately rounded multiply and add,
// never fused: this file's translation unit is compiled with -ffp-contract=off), so the results
// are the same bits on every x86-64 CPU: the SSE2 baseline path and the AVX2 path, chosen at run
// time with __builtin_cpu_supports, agree bit for bit (tested: dense_kernel_test.cc).
#pragma once

namespace vb::nn {

enum class KernelIsa {
  kBaseline,   // SSE2: every x86-64 CPU (4 samples per instruction)
  kAvx2,       // 8 samples per instruction, only when the CPU has AVX2
};

// The widest path this CPU runs (kAvx2 when __builtin_cpu_supports("avx2")), unless the
// environment variable VB_NN_KERNEL=baseline asks for the SSE2 path.
KernelIsa BestKernelIsa();
bool KernelIsaAvailable(KernelIsa isa);
const char* KernelIsaName(KernelIsa isa);

// y[o * y_stride + k] = relu?(b[o] + sum_i w[o * in + i] * x[i * x_stride + k]) for o < out,
// k < n (i summed in increasing order). w is row-major [out, in]. x and y must not overlap.
// Allocates nothing. `isa` must be available (KernelIsaAvailable).
void DenseBatch(KernelIsa isa, const float* w, const float* b, int in, int out, bool relu,
                const float* x, int x_stride, float* y, int y_stride, int n);

// out[k] = exp(in[k]) for k < n (in == out allowed), the same bits on every path: a range
// reduction and polynomial of this file (relative error < 2.5e-7 against std::exp on [-87, 88];
// 0 below -88.38, infinity above 88.38, NaN stays NaN).
void ExpBatch(KernelIsa isa, const float* in, float* out, int n);

}  // namespace vb::nn
