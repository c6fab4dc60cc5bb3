#include "io/model_store.h"

#include "io/safetensors_io.h"
#include "vb/engine/error.h"

namespace vb::io {

DataDirModelStore::DataDirModelStore(std::string data_dir) : data_dir_(std::move(data_dir)) {}

const nn::TensorSet& DataDirModelStore::Load(const std::string& relative_path) const {
  if (relative_path.empty() || relative_path[0] == '/' || relative_path.find("..") != std::string::npos) {
    throw InputError("", 0, relative_path, "model path must be relative to the data directory, without '..'");
  }
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = cache_.find(relative_path);
  if (it == cache_.end()) {
    auto set = std::make_unique<nn::TensorSet>(ReadSafetensors(data_dir_ + "/" + relative_path));
    it = cache_.emplace(relative_path, std::move(set)).first;
  }
  return *it->second;
}

}  // namespace vb::io
