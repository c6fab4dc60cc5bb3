// HDF5 reading and writing of datasets (hdf5_dataset.h), through the HDF5 C API.
#include "io/hdf5_dataset.h"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/result_io.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"

namespace vb::io {

namespace {

using dataset::Attribute;
using dataset::Column;
using dataset::ColumnType;
using dataset::EpisodeRecord;

// HDF5 prints its own error stack by default; vb reports errors itself (naming the file).
void QuietHdf5() {
  static const bool quiet = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)quiet;
}

// An HDF5 identifier closed with its closer.
class Id {
 public:
  Id() = default;
  Id(hid_t id, herr_t (*closer)(hid_t)) : id_(id), closer_(closer) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}
  Id& operator=(Id&& o) noexcept {
    Reset();
    id_ = std::exchange(o.id_, -1);
    closer_ = o.closer_;
    return *this;
  }
  ~Id() { Reset(); }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }
  void Reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
  herr_t (*closer_)(hid_t) = nullptr;
};

Id Need(hid_t id, herr_t (*closer)(hid_t), const std::string& path, const std::string& what) {
  if (id < 0) throw IoError(path, "HDF5: cannot " + what);
  return Id(id, closer);
}
void NeedOk(herr_t status, const std::string& path, const std::string& what) {
  if (status < 0) throw IoError(path, "HDF5: cannot " + what);
}

// h5py's boolean: an int8 enum FALSE = 0, TRUE = 1 (numpy bool arrays read back as bool).
Id BoolType(const std::string& path) {
  Id t = Need(H5Tenum_create(H5T_NATIVE_INT8), H5Tclose, path, "create the bool type");
  int8_t v = 0;
  NeedOk(H5Tenum_insert(t.get(), "FALSE", &v), path, "create the bool type");
  v = 1;
  NeedOk(H5Tenum_insert(t.get(), "TRUE", &v), path, "create the bool type");
  return t;
}

Id VlenString(const std::string& path) {
  Id t = Need(H5Tcopy(H5T_C_S1), H5Tclose, path, "create a string type");
  NeedOk(H5Tset_size(t.get(), H5T_VARIABLE), path, "create a string type");
  NeedOk(H5Tset_cset(t.get(), H5T_CSET_UTF8), path, "create a string type");
  return t;
}

// Property lists without object modification times (determinism).
Id NoTimes(hid_t cls, const std::string& path) {
  Id p = Need(H5Pcreate(cls), H5Pclose, path, "create a property list");
  NeedOk(H5Pset_obj_track_times(p.get(), 0), path, "turn off time tracking");
  return p;
}

void WriteAttribute(hid_t loc, const Attribute& a, const std::string& path) {
  Id space = Need(H5Screate(H5S_SCALAR), H5Sclose, path, "create a dataspace");
  const std::string what = "write attribute " + a.name;
  if (a.kind == Attribute::Kind::kText) {
    Id t = VlenString(path);
    Id attr = Need(H5Acreate2(loc, a.name.c_str(), t.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, path, what);
    const char* p = a.text.c_str();
    NeedOk(H5Awrite(attr.get(), t.get(), &p), path, what);
  } else if (a.kind == Attribute::Kind::kInt) {
    Id attr = Need(H5Acreate2(loc, a.name.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT,
                              H5P_DEFAULT),
                   H5Aclose, path, what);
    NeedOk(H5Awrite(attr.get(), H5T_NATIVE_INT64, &a.integer), path, what);
  } else {
    Id attr = Need(H5Acreate2(loc, a.name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                              H5P_DEFAULT),
                   H5Aclose, path, what);
    NeedOk(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &a.real), path, what);
  }
}

// Opens group `name` under loc, creating it (without times) if missing.
Id GroupAt(hid_t loc, const std::string& name, const std::string& path) {
  if (H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0) {
    return Need(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose, path, "open group " + name);
  }
  Id gcpl = NoTimes(H5P_GROUP_CREATE, path);
  return Need(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose, path,
              "create group " + name);
}

void WriteColumn(hid_t group, const Column& c, const std::string& path) {
  // Intermediate groups ("observations/state" -> group observations).
  Id parent;
  hid_t loc = group;
  std::string name = c.path;
  const size_t slash = name.rfind('/');
  if (slash != std::string::npos) {
    parent = GroupAt(group, name.substr(0, slash), path);
    loc = parent.get();
    name = name.substr(slash + 1);
  }
  const size_t rows = c.Rows();
  std::vector<hsize_t> dims = {static_cast<hsize_t>(rows)};
  for (size_t d : c.row_shape) dims.push_back(static_cast<hsize_t>(d));
  Id space = Need(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                  path, "create a dataspace for " + c.path);
  Id dcpl = NoTimes(H5P_DATASET_CREATE, path);
  if (c.compress && rows > 0) {
    std::vector<hsize_t> chunk = dims;
    chunk[0] = std::min<hsize_t>(rows, 16);
    NeedOk(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), path, "chunk");
    NeedOk(H5Pset_shuffle(dcpl.get()), path, "set the shuffle filter");
    NeedOk(H5Pset_deflate(dcpl.get(), 4), path, "set the deflate filter");
  }
  Id bool_type;
  hid_t file_type = H5T_IEEE_F64LE, mem_type = H5T_NATIVE_DOUBLE;
  const void* data = nullptr;
  switch (c.type) {
    case ColumnType::kFloat32: file_type = H5T_IEEE_F32LE; mem_type = H5T_NATIVE_FLOAT;
                               data = c.f32.data(); break;
    case ColumnType::kFloat64: data = c.f64.data(); break;
    case ColumnType::kInt8: file_type = H5T_STD_I8LE; mem_type = H5T_NATIVE_INT8;
                            data = c.i8.data(); break;
    case ColumnType::kInt32: file_type = H5T_STD_I32LE; mem_type = H5T_NATIVE_INT32;
                             data = c.i32.data(); break;
    case ColumnType::kBool:
      bool_type = BoolType(path);
      file_type = mem_type = bool_type.get();
      data = c.i8.data();
      break;
  }
  Id dset = Need(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(),
                            H5P_DEFAULT),
                 H5Dclose, path, "create dataset " + c.path);
  if (rows > 0) {
    NeedOk(H5Dwrite(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), path,
           "write dataset " + c.path);
  }
}

void WriteRecordInto(hid_t group, const EpisodeRecord& record, const std::string& path) {
  for (const Attribute& a : record.attributes) WriteAttribute(group, a, path);
  for (const Column& c : record.columns) WriteColumn(group, c, path);
}

Id OpenRead(const std::string& path) {
  QuietHdf5();
  if (!std::filesystem::exists(path)) throw InputError(path, 0, "", "no such file");
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw InputError(path, 0, "", "not a readable HDF5 file (truncated or foreign)");
  return Id(f, H5Fclose);
}

// Attribute as text (see ReadEpisodeAttributes).
std::string AttributeText(hid_t attr, const std::string& path, const std::string& name) {
  Id type = Need(H5Aget_type(attr), H5Tclose, path, "read attribute " + name);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls == H5T_STRING) {
    if (H5Tis_variable_str(type.get()) > 0) {
      Id t = VlenString(path);
      char* p = nullptr;
      NeedOk(H5Aread(attr, t.get(), &p), path, "read attribute " + name);
      std::string s = p != nullptr ? p : "";
      H5free_memory(p);
      return s;
    }
    const size_t n = H5Tget_size(type.get());
    std::string s(n, '\0');
    NeedOk(H5Aread(attr, type.get(), s.data()), path, "read attribute " + name);
    s.resize(std::strlen(s.c_str()));
    return s;
  }
  if (cls == H5T_INTEGER) {
    int64_t v = 0;
    NeedOk(H5Aread(attr, H5T_NATIVE_INT64, &v), path, "read attribute " + name);
    return std::to_string(v);
  }
  if (cls == H5T_FLOAT) {
    double v = 0;
    NeedOk(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), path, "read attribute " + name);
    return FormatDouble(v);
  }
  return "";
}

std::map<std::string, std::string> GroupAttributes(hid_t group, const std::string& path) {
  std::map<std::string, std::string> out;
  H5O_info_t info;
  NeedOk(H5Oget_info(group, &info), path, "read the episode group");
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    Id attr = Need(H5Aopen_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, H5P_DEFAULT,
                                  H5P_DEFAULT),
                   H5Aclose, path, "open an attribute");
    const ssize_t n = H5Aget_name(attr.get(), 0, nullptr);
    std::string name(static_cast<size_t>(std::max<ssize_t>(n, 0)) + 1, '\0');
    H5Aget_name(attr.get(), name.size(), name.data());
    name.resize(static_cast<size_t>(std::max<ssize_t>(n, 0)));
    out[name] = AttributeText(attr.get(), path, name);
  }
  return out;
}

// Visits the datasets under a group (paths relative to it).
herr_t CollectDatasets(hid_t group, const char* name, const H5L_info_t*, void* data) {
  const hid_t obj = H5Oopen(group, name, H5P_DEFAULT);
  if (obj < 0) return -1;
  if (H5Iget_type(obj) == H5I_DATASET) {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
  }
  H5Oclose(obj);
  return 0;
}

void Fsync(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw IoError(path, "cannot sync: " + why);
  }
  ::close(fd);
}

}  // namespace

void WriteEpisodeFile(const EpisodeRecord& record, const std::string& path) {
  QuietHdf5();
  std::string image;
  {
    Id fapl = Need(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, path, "create a property list");
    NeedOk(H5Pset_fapl_core(fapl.get(), 1 << 20, /*backing_store=*/0), path, "use memory");
    Id fcpl = NoTimes(H5P_FILE_CREATE, path);
    Id file = Need(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), H5Fclose, path,
                   "create the file in memory");
    {
      Id group = GroupAt(file.get(), "episode", path);
      WriteRecordInto(group.get(), record, path);
    }
    NeedOk(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), path, "flush");
    const ssize_t size = H5Fget_file_image(file.get(), nullptr, 0);
    if (size <= 0) throw IoError(path, "HDF5: cannot get the file image");
    image.resize(static_cast<size_t>(size));
    if (H5Fget_file_image(file.get(), image.data(), image.size()) != size) {
      throw IoError(path, "HDF5: cannot get the file image");
    }
  }
  WriteFileAtomic(path, image);
}

std::map<std::string, std::string> ReadEpisodeAttributes(const std::string& path) {
  Id file = OpenRead(path);
  const hid_t g = H5Gopen2(file.get(), "episode", H5P_DEFAULT);
  if (g < 0) throw InputError(path, 0, "episode", "no episode group: not a vb episode file");
  Id group(g, H5Gclose);
  try {
    return GroupAttributes(group.get(), path);
  } catch (const IoError& e) {
    throw InputError(path, 0, "episode", e.what());
  }
}

EpisodeRecord ReadEpisodeFile(const std::string& path) {
  Id file = OpenRead(path);
  const hid_t g = H5Gopen2(file.get(), "episode", H5P_DEFAULT);
  if (g < 0) throw InputError(path, 0, "episode", "no episode group: not a vb episode file");
  Id group(g, H5Gclose);
  EpisodeRecord r;
  try {
    for (const auto& [name, value] : GroupAttributes(group.get(), path)) r.SetText(name, value);
    std::vector<std::string> names;
    NeedOk(H5Lvisit(group.get(), H5_INDEX_NAME, H5_ITER_INC, CollectDatasets, &names), path,
           "list datasets");
    for (const std::string& name : names) {
      Id d = Need(H5Dopen2(group.get(), name.c_str(), H5P_DEFAULT), H5Dclose, path, "open " + name);
      Id space = Need(H5Dget_space(d.get()), H5Sclose, path, "read " + name);
      Id type = Need(H5Dget_type(d.get()), H5Tclose, path, "read " + name);
      const int rank = H5Sget_simple_extent_ndims(space.get());
      std::vector<hsize_t> dims(static_cast<size_t>(std::max(rank, 0)));
      H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
      std::vector<size_t> row_shape;
      size_t total = rank > 0 ? static_cast<size_t>(dims[0]) : 1;
      for (int i = 1; i < rank; ++i) {
        row_shape.push_back(static_cast<size_t>(dims[static_cast<size_t>(i)]));
        total *= static_cast<size_t>(dims[static_cast<size_t>(i)]);
      }
      const H5T_class_t cls = H5Tget_class(type.get());
      const size_t bytes = H5Tget_size(type.get());
      ColumnType ct = ColumnType::kFloat64;
      if (cls == H5T_FLOAT) ct = bytes == 4 ? ColumnType::kFloat32 : ColumnType::kFloat64;
      else if (cls == H5T_ENUM) ct = ColumnType::kBool;
      else if (cls == H5T_INTEGER) ct = bytes == 1 ? ColumnType::kInt8 : ColumnType::kInt32;
      Column& c = r.Add(name, ct, row_shape);
      void* buffer = nullptr;
      hid_t mem_type = H5T_NATIVE_DOUBLE;
      switch (ct) {
        case ColumnType::kFloat32: c.f32.resize(total); buffer = c.f32.data();
                                   mem_type = H5T_NATIVE_FLOAT; break;
        case ColumnType::kFloat64: c.f64.resize(total); buffer = c.f64.data(); break;
        case ColumnType::kInt8: c.i8.resize(total); buffer = c.i8.data();
                                mem_type = H5T_NATIVE_INT8; break;
        case ColumnType::kBool: c.i8.resize(total); buffer = c.i8.data();
                                mem_type = type.get(); break;
        case ColumnType::kInt32: c.i32.resize(total); buffer = c.i32.data();
                                 mem_type = H5T_NATIVE_INT32; break;
      }
      const herr_t st =
          total > 0 ? H5Dread(d.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer) : 0;
      NeedOk(st, path, "read " + name);
    }
  } catch (const IoError& e) {
    throw InputError(path, 0, "episode", e.what());
  }
  const dataset::Column* actions = r.Find("actions");
  r.steps = actions != nullptr ? static_cast<long>(actions->Rows()) : 0;
  return r;
}

AssembleCounts AssembleDataset(const std::vector<std::string>& episode_files,
                               const DatasetInfo& info, const std::string& data_dir) {
  namespace fs = std::filesystem;
  QuietHdf5();
  std::error_code ec;
  fs::create_directories(data_dir, ec);
  if (ec) throw IoError(data_dir, "cannot create directory: " + ec.message());
  const std::string target = (fs::path(data_dir) / "main_data.hdf5").string();
  const std::string tmp = (fs::path(data_dir) / (".main_data.hdf5.tmp." +
                                                 std::to_string(::getpid()))).string();
  AssembleCounts counts;
  try {
    Id fcpl = NoTimes(H5P_FILE_CREATE, tmp);
    Id file = Need(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), H5Fclose, tmp,
                   "create the file");
    for (const std::string& src_path : episode_files) {
      Id src = OpenRead(src_path);
      const std::string name = "episode_" + std::to_string(counts.episodes);
      NeedOk(H5Ocopy(src.get(), "episode", file.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
             tmp, "copy " + src_path);
      Id g = Need(H5Gopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Gclose, tmp, "open " + name);
      if (H5Aexists(g.get(), "id") > 0) NeedOk(H5Adelete(g.get(), "id"), tmp, "renumber " + name);
      Attribute id;
      id.name = "id";
      id.kind = Attribute::Kind::kInt;
      id.integer = counts.episodes;
      WriteAttribute(g.get(), id, tmp);
      int64_t steps = 0;
      if (H5Aexists(g.get(), "total_steps") > 0) {
        Id a = Need(H5Aopen(g.get(), "total_steps", H5P_DEFAULT), H5Aclose, tmp, "read steps");
        NeedOk(H5Aread(a.get(), H5T_NATIVE_INT64, &steps), tmp, "read steps");
      }
      counts.steps += steps;
      ++counts.episodes;
    }
    std::vector<Attribute> root;
    auto text = [&](const std::string& name, const std::string& value) {
      Attribute a;
      a.name = name;
      a.text = value;
      root.push_back(a);
    };
    auto integer = [&](const std::string& name, int64_t value) {
      Attribute a;
      a.name = name;
      a.kind = Attribute::Kind::kInt;
      a.integer = value;
      root.push_back(a);
    };
    text("dataset_id", info.dataset_id);
    text("observation_space", info.observation_space);
    text("action_space", info.action_space);
    text("algorithm_name", info.algorithm_name);
    integer("total_episodes", counts.episodes);
    integer("total_steps", counts.steps);
    for (const auto& [k, v] : info.attributes) text(k, v);
    for (const Attribute& a : root) WriteAttribute(file.get(), a, tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  Fsync(tmp);
  if (std::rename(tmp.c_str(), target.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    fs::remove(tmp, ec);
    throw IoError(target, "cannot rename the finished file into place: " + why);
  }
  // Minari's metadata (minari.dataset.minari_storage: read by minari.load_dataset).
  std::string json = "{";
  json += "\"dataset_id\": " + JsonString(info.dataset_id);
  json += ", \"total_episodes\": " + std::to_string(counts.episodes);
  json += ", \"total_steps\": " + std::to_string(counts.steps);
  json += ", \"data_format\": \"hdf5\", \"jpeg_encoding\": false";
  json += ", \"observation_space\": " + JsonString(info.observation_space);
  json += ", \"action_space\": " + JsonString(info.action_space);
  json += ", \"algorithm_name\": " + JsonString(info.algorithm_name);
  json += ", \"author\": [\"vb\"]";
  json += ", \"minari_version\": \"0.5.4\"";
  for (const auto& [k, v] : info.attributes) json += ", " + JsonString(k) + ": " + JsonString(v);
  json += "}\n";
  WriteFileAtomic((fs::path(data_dir) / "metadata.json").string(), json);
  return counts;
}

}  // namespace vb::io
