#include "vb/nn/tensor_set.h"

#include "vb/engine/error.h"

namespace vb::nn {

long Tensor::size() const {
  long n = 1;
  for (int d : shape) n *= d;
  return n;
}

std::string ShapeString(const std::vector<int>& shape) {
  std::string s = "[";
  for (size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + "]";
}

bool TensorSet::contains(const std::string& name) const { return tensors.count(name) > 0; }

const Tensor& TensorSet::at(const std::string& name) const {
  auto it = tensors.find(name);
  if (it == tensors.end()) {
    throw InputError(source, 0, name, "tensor missing from the model file (" +
                                          std::to_string(tensors.size()) + " tensors present)");
  }
  return it->second;
}

const Tensor& TensorSet::at(const std::string& name, const std::vector<int>& shape) const {
  const Tensor& t = at(name);
  if (t.shape != shape) {
    throw InputError(source, 0, name,
                     "tensor has shape " + ShapeString(t.shape) + ", expected " + ShapeString(shape));
  }
  return t;
}

const std::string& TensorSet::meta(const std::string& key) const {
  auto it = metadata.find(key);
  if (it == metadata.end()) {
    throw InputError(source, 0, "__metadata__." + key, "metadata entry missing from the model file");
  }
  return it->second;
}

}  // namespace vb::nn
