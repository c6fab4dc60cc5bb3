#include "io/safetensors_io.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "vb/engine/error.h"

namespace vb::io {

namespace {

using nlohmann::json;

// A header larger than this is not a weights file we wrote (the format's own limit is 100 MB).
constexpr uint64_t kMaxHeaderBytes = 100u << 20;

uint64_t ReadLe64(const unsigned char* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

nn::TensorSet ReadSafetensors(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", std::string("cannot open the model file: ") + std::strerror(errno));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 8) throw InputError(path, 0, "", "not a safetensors file (shorter than its 8-byte header length)");
  const auto* u = reinterpret_cast<const unsigned char*>(bytes.data());
  const uint64_t header_bytes = ReadLe64(u);
  if (header_bytes > kMaxHeaderBytes || header_bytes > bytes.size() - 8) {
    throw InputError(path, 0, "", "not a safetensors file (header length " + std::to_string(header_bytes) +
                                      " does not fit the file of " + std::to_string(bytes.size()) + " bytes)");
  }
  json header;
  try {
    header = json::parse(bytes.begin() + 8, bytes.begin() + 8 + static_cast<long>(header_bytes));
  } catch (const json::exception& e) {
    throw InputError(path, 0, "", std::string("malformed safetensors header: ") + e.what());
  }
  if (!header.is_object()) throw InputError(path, 0, "", "malformed safetensors header: not a JSON object");
  const uint64_t data_begin = 8 + header_bytes;
  const uint64_t data_size = bytes.size() - data_begin;

  nn::TensorSet set;
  set.source = path;
  for (auto it = header.begin(); it != header.end(); ++it) {
    const std::string& name = it.key();
    const json& v = it.value();
    if (name == "__metadata__") {
      if (!v.is_object()) throw InputError(path, 0, name, "metadata must be an object of strings");
      for (auto m = v.begin(); m != v.end(); ++m) {
        if (!m.value().is_string()) throw InputError(path, 0, "__metadata__." + m.key(), "metadata values must be strings");
        set.metadata[m.key()] = m.value().get<std::string>();
      }
      continue;
    }
    if (!v.is_object() || !v.contains("dtype") || !v.contains("shape") || !v.contains("data_offsets")) {
      throw InputError(path, 0, name, "tensor entry needs dtype, shape and data_offsets");
    }
    const json& dtype = v["dtype"];
    const json& shape = v["shape"];
    const json& offsets = v["data_offsets"];
    if (!dtype.is_string() || !shape.is_array() || !offsets.is_array() || offsets.size() != 2 ||
        !offsets[0].is_number_unsigned() || !offsets[1].is_number_unsigned()) {
      throw InputError(path, 0, name, "malformed tensor entry (dtype string, shape list, two offsets)");
    }
    nn::Tensor t;
    uint64_t count = 1;
    for (const json& d : shape) {
      if (!d.is_number_unsigned() || d.get<uint64_t>() > (1u << 30)) {
        throw InputError(path, 0, name, "shape entries must be non-negative integers below 2^30");
      }
      t.shape.push_back(static_cast<int>(d.get<uint64_t>()));
      count *= d.get<uint64_t>();
      if (count > (uint64_t{1} << 32)) throw InputError(path, 0, name, "tensor too large");
    }
    const std::string type = dtype.get<std::string>();
    const uint64_t elem = type == "F32" ? 4 : type == "F64" ? 8 : 0;
    if (elem == 0) throw InputError(path, 0, name, "unsupported dtype '" + type + "' (valid: F32, F64)");
    const uint64_t begin = offsets[0].get<uint64_t>(), end = offsets[1].get<uint64_t>();
    if (begin > end || end > data_size || end - begin != count * elem) {
      throw InputError(path, 0, name, "byte range [" + std::to_string(begin) + ", " + std::to_string(end) +
                                          ") does not fit " + type + nn::ShapeString(t.shape) + " in " +
                                          std::to_string(data_size) + " data bytes");
    }
    t.data.resize(count);
    const char* src = bytes.data() + data_begin + begin;
    if (elem == 4) {
      std::memcpy(t.data.data(), src, count * 4);   // little-endian host (x86-64, aarch64)
    } else {
      for (uint64_t i = 0; i < count; ++i) {
        double d;
        std::memcpy(&d, src + 8 * i, 8);
        t.data[i] = static_cast<float>(d);
      }
    }
    set.tensors.emplace(name, std::move(t));
  }
  return set;
}

void WriteSafetensors(const std::string& path, const nn::TensorSet& tensors) {
  json header = json::object();
  if (!tensors.metadata.empty()) header["__metadata__"] = tensors.metadata;
  uint64_t offset = 0;
  for (const auto& [name, t] : tensors.tensors) {   // std::map: sorted names, stable bytes
    VB_DEMAND(static_cast<long>(t.data.size()) == t.size());
    const uint64_t n = 4 * t.data.size();
    header[name] = {{"dtype", "F32"}, {"shape", t.shape}, {"data_offsets", {offset, offset + n}}};
    offset += n;
  }
  std::string text = header.dump();
  while ((text.size() + 8) % 8 != 0) text += ' ';   // the format pads the header with spaces
  std::string bytes(8, '\0');
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<char>((static_cast<uint64_t>(text.size()) >> (8 * i)) & 0xff);
  bytes += text;
  for (const auto& [name, t] : tensors.tensors) {
    bytes.append(reinterpret_cast<const char*>(t.data.data()), 4 * t.data.size());
  }
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw IoError(tmp, std::strerror(errno));
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const bool closed = std::fclose(f) == 0;
  if (!ok || !closed) {
    std::remove(tmp.c_str());
    throw IoError(tmp, "write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw IoError(path, std::strerror(errno));
}

}  // namespace vb::io
