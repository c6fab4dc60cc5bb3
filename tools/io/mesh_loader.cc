#include "io/mesh_loader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>
#include <utility>

#include "io/yaml_strict.h"
#include "vb/engine/convex_shape.h"
#include "vb/engine/error.h"

namespace vb::io {

namespace {

namespace fs = std::filesystem;

// One file opened for assimp: reads through a descriptor, counting every byte against the
// loader's budget (shared by all files of one load).
class CheckedStream : public Assimp::IOStream {
 public:
  CheckedStream(int fd, size_t size, uint64_t* budget_bytes)
      : fd_(fd), size_(size), budget_(budget_bytes) {}
  ~CheckedStream() override { ::close(fd_); }
  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0 || count == 0) return 0;
    const size_t want = std::min<uint64_t>(size * count, *budget_) / size * size;
    size_t got = 0;
    while (got < want) {
      const ssize_t n = ::pread(fd_, static_cast<char*>(buffer) + got, want - got,
                                static_cast<off_t>(pos_ + got));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += static_cast<size_t>(n);
    }
    got = got / size * size;
    pos_ += got;
    *budget_ -= got;
    return got / size;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? pos_ : size_;
    if (offset > size_ || base + offset > size_) return aiReturn_FAILURE;
    pos_ = base + offset;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return pos_; }
  size_t FileSize() const override { return size_; }
  void Flush() override {}

 private:
  int fd_;
  size_t size_;
  size_t pos_ = 0;
  uint64_t* budget_;
};

// Every file assimp opens goes through here: the mesh file and the files it refers to (an OBJ's
// mtllib, a glTF's buffers and images). Each must be a regular file of at most
// kMaxMeshFileBytes inside the mesh file's directory (so a mesh cannot make vb block on a FIFO
// or read /etc/passwd: NEW-12 of the probe at 8ff4def), opened without blocking and checked on
// the open descriptor; all of them together are read at most kMaxMeshReadBytes. Read-only.
class CheckedIOSystem : public Assimp::IOSystem {
 public:
  explicit CheckedIOSystem(const std::string& mesh_path) {
    std::error_code ec;
    root_ = fs::weakly_canonical(fs::absolute(mesh_path, ec).parent_path(), ec);
  }
  // The first refusal, for the error message (assimp's own says only "cannot open").
  const std::string& problem() const { return problem_; }

  bool Exists(const char* path) const override {
    std::string why;
    const int fd = OpenChecked(path, &why);
    if (fd < 0) return false;
    ::close(fd);
    return true;
  }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* path, const char* mode) override {
    if (std::strchr(mode, 'w') != nullptr || std::strchr(mode, 'a') != nullptr ||
        std::strchr(mode, '+') != nullptr) {
      Refuse(path, "would be written (meshes are read only)");
      return nullptr;
    }
    if (++opened_ > kMaxMeshFilesOpened) {
      Refuse(path, "is one file too many: a mesh may open at most " +
                       std::to_string(kMaxMeshFilesOpened) + " files");
      return nullptr;
    }
    std::string why;
    const int fd = OpenChecked(path, &why);
    if (fd < 0) {
      Refuse(path, why);
      return nullptr;
    }
    struct stat st {};
    ::fstat(fd, &st);
    return new CheckedStream(fd, static_cast<size_t>(st.st_size), &budget_bytes_);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  void Refuse(const char* path, const std::string& why) {
    if (problem_.empty()) problem_ = "'" + std::string(path) + "' " + why;
  }
  // A descriptor of `path` if it may be read, else -1 with *why.
  int OpenChecked(const char* path, std::string* why) const {
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(fs::absolute(path, ec), ec);
    const std::string root = root_.string();
    if (ec || real.string().compare(0, root.size() + 1, root + "/") != 0) {
      *why = "is outside the mesh file's directory " + root;
      return -1;
    }
    // O_NONBLOCK: opening a FIFO must not wait for a writer; then the descriptor itself is
    // checked, so nothing can be swapped in between.
    const int fd = ::open(real.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      *why = errno == ENOENT ? "does not exist" : "cannot be opened: " + std::string(std::strerror(errno));
      return -1;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      *why = S_ISDIR(st.st_mode) ? "is a directory, not a file"
             : S_ISFIFO(st.st_mode) ? "is a FIFO, not a regular file"
                                    : "is a device or special file, not a regular file";
      return -1;
    }
    if (static_cast<uint64_t>(st.st_size) > kMaxMeshFileBytes) {
      ::close(fd);
      *why = "is " + std::to_string(st.st_size) + " bytes, more than the " +
             std::to_string(kMaxMeshFileBytes) + " bytes accepted";
      return -1;
    }
    return fd;
  }

  fs::path root_;
  std::string problem_;
  int opened_ = 0;
  uint64_t budget_bytes_ = kMaxMeshReadBytes;
};

}  // namespace

std::vector<Vec3> LoadMeshVertices(const std::string& mesh_path, const std::string& referrer_file,
                                   int line, const std::string& key) {
  auto fail = [&](const std::string& what) {
    throw InputError(referrer_file, line, key, "mesh '" + mesh_path + "': " + what);
  };
  const std::string problem = InputFileProblem(mesh_path, kMaxMeshFileBytes);
  if (!problem.empty()) fail(problem);

  Assimp::Importer importer;
  CheckedIOSystem* io = new CheckedIOSystem(mesh_path);
  importer.SetIOHandler(io);   // the importer owns and deletes it
  // Triangles only; points and lines are dropped (they bound no volume).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      mesh_path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!io->problem().empty()) fail("refers to a file that " + io->problem());
  if (scene == nullptr) fail(std::string("cannot be read as a mesh: ") + importer.GetErrorString());

  // Vertices merged by exact position (a file may split them by normal or texture coordinate),
  // and every triangle's edges counted on the merged ids.
  std::map<std::tuple<double, double, double>, int> id_of;
  std::vector<Vec3> vertices;
  std::map<std::pair<int, int>, int> edge_uses;
  size_t triangles = 0, raw_vertices = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    // assimp's vertices are per face corner (an OBJ quad gives 4): bounded generously here, the
    // limit of the docs applies to the merged ones below (NEW-13 of the probe at 8ff4def).
    raw_vertices += mesh->mNumVertices;
    if (raw_vertices > kMaxMeshCornerVertices) {
      fail("huge: more than " + std::to_string(kMaxMeshCornerVertices) + " face corners");
    }
    std::vector<int> ids(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Vec3 q(p.x, p.y, p.z);
      if (!q.allFinite()) fail("vertex " + std::to_string(v) + " is not finite");
      auto [it, inserted] =
          id_of.emplace(std::make_tuple(q.x(), q.y(), q.z()), static_cast<int>(vertices.size()));
      if (inserted) {
        vertices.push_back(q);
        if (vertices.size() > kMaxMeshVertices) {
          fail("huge: more than " + std::to_string(kMaxMeshVertices) + " vertices");
        }
      }
      ids[v] = it->second;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      ++triangles;
      for (int k = 0; k < 3; ++k) {
        int a = ids[face.mIndices[k]], b = ids[face.mIndices[(k + 1) % 3]];
        if (a == b) continue;   // a degenerate triangle's collapsed edge
        if (a > b) std::swap(a, b);
        ++edge_uses[{a, b}];
      }
    }
  }
  if (triangles == 0) fail("empty: no triangles");
  for (const auto& [edge, uses] : edge_uses) {
    if (uses != 2) {
      const Vec3& a = vertices[static_cast<size_t>(edge.first)];
      const Vec3& b = vertices[static_cast<size_t>(edge.second)];
      fail("non-manifold: the edge (" + FormatDouble(a.x()) + ", " + FormatDouble(a.y()) + ", " +
           FormatDouble(a.z()) + ") - (" + FormatDouble(b.x()) + ", " + FormatDouble(b.y()) +
           ", " + FormatDouble(b.z()) + ") belongs to " + std::to_string(uses) +
           " triangles; a closed solid has 2 at every edge");
    }
  }
  Vec3 lo = vertices[0], hi = vertices[0];
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double extent = (hi - lo).maxCoeff();
  if (extent > kMaxMeshExtent_m) {
    fail("huge: " + FormatDouble(extent) + " m across; at most " +
         FormatDouble(kMaxMeshExtent_m) + " m (vertices are metres)");
  }
  engine::ConvexShape hull;
  std::string error;
  if (!engine::TryMakeConvexHull(vertices, 0.05, &hull, &error)) fail("flat: " + error);
  return vertices;
}

}  // namespace vb::io
