// Reading and writing safetensors files (the tensor format of Hugging Face's safetensors: an
// 8-byte little-endian header length, a JSON header naming each tensor's dtype, shape and byte
// range, then the raw little-endian bytes). vb's trained weights are stored this way
// (data/policies, data/models) so that Python (safetensors, torch) and C++ read the same file.
// F32 and F64 tensors are read (F64 converted to float); everything is written as F32.
#pragma once

#include <string>

#include "vb/nn/tensor_set.h"

namespace vb::io {

// Throws InputError naming the file and the offending tensor/key for a file that is missing,
// truncated, has a malformed header, an unsupported dtype or byte ranges that do not fit.
nn::TensorSet ReadSafetensors(const std::string& path);

// Writes atomically (temporary file + rename). Throws IoError when the file cannot be written.
void WriteSafetensors(const std::string& path, const nn::TensorSet& tensors);

}  // namespace vb::io
