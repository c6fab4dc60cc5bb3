// The tools' ModelStore: trained weights read from the data directory (data/policies,
// data/models) as safetensors, each file read once per process and kept.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "vb/nn/model_store.h"

namespace vb::io {

class DataDirModelStore : public nn::ModelStore {
 public:
  explicit DataDirModelStore(std::string data_dir);
  // Relative paths only, inside the data directory (no "..", no leading '/'); InputError otherwise.
  const nn::TensorSet& Load(const std::string& relative_path) const override;

 private:
  std::string data_dir_;
  mutable std::mutex mutex_;   // vb_batch runs trials on several threads
  mutable std::map<std::string, std::unique_ptr<nn::TensorSet>> cache_;
};

}  // namespace vb::io
