// Where learned systems get their weights: an interface so that the core (controllers) never
// touches files. The tools implement it over the data directory (tools/io/model_store.h); tests
// may implement it in memory. Paths are relative to the data directory, e.g.
// "policies/rl.safetensors".
#pragma once

#include <string>

#include "vb/nn/tensor_set.h"

namespace vb::nn {

class ModelStore {
 public:
  virtual ~ModelStore() = default;
  // The tensors of `relative_path`; the reference stays valid as long as the store. Throws
  // InputError when the file is missing or malformed.
  virtual const TensorSet& Load(const std::string& relative_path) const = 0;
};

}  // namespace vb::nn
