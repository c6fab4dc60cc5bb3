// Named float tensors (a trained model's weights) with the file's string metadata: what a
// safetensors file holds (tools/io/safetensors_io reads it). Plain data; the core never reads
// files. Lookups fail with an InputError naming the source file and the tensor, so a model file
// that does not fit its network is reported like any other bad input (exit code 2 in the tools).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace vb::nn {

struct Tensor {
  std::vector<int> shape;    // e.g. {out, in} for a PyTorch Linear weight
  std::vector<float> data;   // row-major (C order), as PyTorch and safetensors store it
  long size() const;         // product of shape (1 for a scalar)
};

class TensorSet {
 public:
  std::string source;  // where the tensors came from (a file path), for error messages
  std::map<std::string, Tensor> tensors;
  std::map<std::string, std::string> metadata;

  bool contains(const std::string& name) const;
  const Tensor& at(const std::string& name) const;
  // As at(), and the shape must equal `shape` exactly.
  const Tensor& at(const std::string& name, const std::vector<int>& shape) const;
  // Metadata value; throws naming the source and key if absent.
  const std::string& meta(const std::string& key) const;
};

std::string ShapeString(const std::vector<int>& shape);   // "[64, 32]"

}  // namespace vb::nn
