#include "vb/nn/mlp.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "vb/engine/error.h"

namespace vb::nn {

Activation ParseActivation(const std::string& name) {
  static const std::map<std::string, Activation> kNames = {
      {"none", Activation::kNone}, {"relu", Activation::kRelu},       {"tanh", Activation::kTanh},
      {"elu", Activation::kElu},   {"sigmoid", Activation::kSigmoid}, {"softplus", Activation::kSoftplus}};
  auto it = kNames.find(name);
  if (it == kNames.end()) {
    throw InputError("", 0, "activation",
                     "unknown activation '" + name + "'; valid: none, relu, tanh, elu, sigmoid, softplus");
  }
  return it->second;
}

void Apply(Activation a, Eigen::Ref<Eigen::MatrixXf> x) {
  switch (a) {
    case Activation::kNone:
      return;
    case Activation::kRelu:
      x = x.cwiseMax(0.0f);
      return;
    case Activation::kTanh:
      x = x.array().tanh().matrix();
      return;
    case Activation::kElu:  // PyTorch ELU with alpha = 1
      x = x.unaryExpr([](float v) { return v > 0.0f ? v : std::expm1(v); });
      return;
    case Activation::kSigmoid:
      x = x.unaryExpr([](float v) { return 1.0f / (1.0f + std::exp(-v)); });
      return;
    case Activation::kSoftplus:  // PyTorch Softplus (beta 1, threshold 20)
      x = x.unaryExpr([](float v) { return v > 20.0f ? v : std::log1p(std::exp(v)); });
      return;
  }
}

Mlp::Mlp(const TensorSet& tensors, const std::string& prefix,
         const std::vector<Activation>& activations) {
  // Sequential indices that carry a Linear layer, in increasing order.
  std::vector<int> indices;
  const std::string head = prefix + ".";
  for (const auto& [name, tensor] : tensors.tensors) {
    if (name.compare(0, head.size(), head) != 0) continue;
    const std::string rest = name.substr(head.size());
    const size_t dot = rest.find('.');
    if (dot == std::string::npos || rest.substr(dot + 1) != "weight") continue;
    const std::string index = rest.substr(0, dot);
    if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos) continue;
    indices.push_back(std::stoi(index));
  }
  std::sort(indices.begin(), indices.end());
  if (indices.empty()) {
    throw InputError(tensors.source, 0, prefix + ".<i>.weight", "no Linear layer with this prefix");
  }
  if (indices.size() != activations.size()) {
    throw InputError(tensors.source, 0, prefix,
                     std::to_string(indices.size()) + " Linear layers, but the network has " +
                         std::to_string(activations.size()) + " (a different architecture)");
  }
  int widest = 0;
  for (size_t k = 0; k < indices.size(); ++k) {
    const std::string base = prefix + "." + std::to_string(indices[k]);
    const Tensor& w = tensors.at(base + ".weight");
    if (w.shape.size() != 2) {
      throw InputError(tensors.source, 0, base + ".weight",
                       "expected a 2-D [out, in] weight, got " + ShapeString(w.shape));
    }
    const int out = w.shape[0], in = w.shape[1];
    if (k > 0 && in != weights_.back().rows()) {
      throw InputError(tensors.source, 0, base + ".weight",
                       "input width " + std::to_string(in) + " does not match the previous layer's " +
                           std::to_string(weights_.back().rows()) + " outputs");
    }
    const Tensor& b = tensors.at(base + ".bias", {out});
    // The file is row-major [out, in]; Eigen's default is column-major.
    weights_.push_back(Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic,
                                                      Eigen::RowMajor>>(w.data.data(), out, in));
    biases_.push_back(Eigen::Map<const Eigen::VectorXf>(b.data.data(), out));
    dense_w_.emplace_back(w.data.begin(), w.data.begin() + static_cast<long>(out) * in);
    widest = std::max({widest, out, in});
  }
  activations_ = activations;
  input_size_ = static_cast<int>(weights_.front().cols());
  output_size_ = static_cast<int>(weights_.back().rows());
  a_.resize(widest);
  b_.resize(widest);
}

void Mlp::Forward(const float* in, float* out) const {
  const int n0 = input_size_;
  a_.head(n0) = Eigen::Map<const Eigen::VectorXf>(in, n0);
  Eigen::VectorXf* x = &a_;
  Eigen::VectorXf* y = &b_;
  for (size_t k = 0; k < weights_.size(); ++k) {
    const Eigen::MatrixXf& w = weights_[k];
    const long rows = w.rows(), cols = w.cols();
    y->head(rows).noalias() = w * x->head(cols);
    y->head(rows) += biases_[k];
    Apply(activations_[k], y->head(rows));
    std::swap(x, y);
  }
  Eigen::Map<Eigen::VectorXf>(out, output_size_) = x->head(output_size_);
}

void Mlp::set_kernel_isa(KernelIsa isa) {
  VB_DEMAND(KernelIsaAvailable(isa));
  isa_ = isa;
}

void Mlp::ForwardBatch(const BatchMatrix& in, BatchMatrix& out) const {
  VB_DEMAND(in.rows() == input_size_);
  const int n = static_cast<int>(in.cols());
  if (out.rows() != output_size_ || out.cols() != n) out.resize(output_size_, n);
  ForwardBatch(in.data(), n, n, out.data(), n);
}

void Mlp::ForwardBatch(const float* in, int in_stride, int n, float* out, int out_stride) const {
  const int layers = static_cast<int>(weights_.size());
  const float* x = in;
  int x_stride = in_stride;
  for (int k = 0; k < layers; ++k) {
    const int rows = static_cast<int>(weights_[k].rows());
    float* y;
    int y_stride;
    if (k + 1 == layers) {
      y = out;
      y_stride = out_stride;
    } else {
      BatchMatrix& m = k % 2 == 0 ? batch_a_ : batch_b_;
      if (m.rows() < rows || m.cols() < n) m.resize(std::max<long>(m.rows(), rows), std::max<long>(m.cols(), n));
      y = m.data();
      y_stride = static_cast<int>(m.cols());
    }
    const bool relu = activations_[k] == Activation::kRelu;
    DenseBatch(isa_, dense_w_[k].data(), biases_[k].data(), static_cast<int>(weights_[k].cols()),
               rows, relu, x, x_stride, y, y_stride, n);
    if (!relu && activations_[k] != Activation::kNone) {
      for (int r = 0; r < rows; ++r) {
        Apply(activations_[k], Eigen::Map<Eigen::MatrixXf>(y + static_cast<long>(r) * y_stride, n, 1));
      }
    }
    x = y;
    x_stride = y_stride;
  }
}

}  // namespace vb::nn
