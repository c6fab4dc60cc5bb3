// A multilayer perceptron: PyTorch's nn.Sequential of Linear layers and element-wise
// activations, evaluated with Eigen in float32. Built from a TensorSet by prefix: the Linear
// layers are the tensors `{prefix}.{i}.weight` ([out, in]) and `{prefix}.{i}.bias` ([out]) for
// the Sequential indices i that have them, in increasing i (activation modules have no
// tensors, so their indices are skipped). The activations are given by the caller, one per
// Linear layer (a network's structure is code, its numbers are data).
//
// Forward() allocates nothing after construction (buffers sized at build time); ForwardBatch()
// evaluates many inputs at once (columns), as the sampling planners' rollouts need: through
// dense_kernel.h, samples in the vector lanes, the same bits on every CPU (baseline SSE2 or AVX2
// chosen at run time), and no allocation once its scratch has the batch's size.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "vb/nn/dense_kernel.h"
#include "vb/nn/tensor_set.h"

namespace vb::nn {

// A batch of samples, one column each, stored feature-major (row-major): row i holds feature i
// of every sample contiguously, the layout the batched kernel vectorises over.
using BatchMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

enum class Activation { kNone, kRelu, kTanh, kElu, kSigmoid, kSoftplus };

// Parses "none", "relu", "tanh", "elu", "sigmoid", "softplus"; throws InputError otherwise.
Activation ParseActivation(const std::string& name);

// In place on every element.
void Apply(Activation a, Eigen::Ref<Eigen::MatrixXf> x);

class Mlp {
 public:
  Mlp() = default;
  // `activations` has one entry per Linear layer (the last is usually kNone). Throws InputError
  // (source file, tensor name) on a missing tensor or mismatching shapes.
  Mlp(const TensorSet& tensors, const std::string& prefix, const std::vector<Activation>& activations);

  int input_size() const { return input_size_; }
  int output_size() const { return output_size_; }
  int layer_count() const { return static_cast<int>(weights_.size()); }

  // out = f(in); `in` has input_size() values, `out` room for output_size(). No allocation.
  void Forward(const float* in, float* out) const;
  // Columns are samples: in is input_size() x n, out is resized to output_size() x n (allocates
  // only when n changes). Each column's result does not depend on n, on the other columns or on
  // the CPU's vector width.
  void ForwardBatch(const BatchMatrix& in, BatchMatrix& out) const;
  // The same on raw feature-major rows: in[i * in_stride + k], out[o * out_stride + k], k < n.
  void ForwardBatch(const float* in, int in_stride, int n, float* out, int out_stride) const;

  // The kernel path (default: BestKernelIsa()); tests compare the paths bit for bit.
  void set_kernel_isa(KernelIsa isa);
  KernelIsa kernel_isa() const { return isa_; }

 private:
  std::vector<Eigen::MatrixXf> weights_;   // [out, in]
  std::vector<Eigen::VectorXf> biases_;
  std::vector<Activation> activations_;
  std::vector<std::vector<float>> dense_w_;   // row-major [out, in] copies for the batch kernel
  KernelIsa isa_ = BestKernelIsa();
  int input_size_ = 0;
  int output_size_ = 0;
  // Scratch for Forward (two ping-pong vectors of the widest layer); mutable so Forward is const
  // and allocation-free. An Mlp is therefore not shared between threads (each trial builds its own).
  mutable Eigen::VectorXf a_, b_;
  mutable BatchMatrix batch_a_, batch_b_;
};

}  // namespace vb::nn
