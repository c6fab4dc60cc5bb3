// Tests for tools/io/mesh_loader.cc: the committed mesh loads from OBJ, and the same solid from
// STL and glTF; bad meshes (missing, empty, non-manifold, huge, flat) are located errors.
#include "io/mesh_loader.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

const std::string kRock = std::string(VB_SOURCE_DIR) + "/data/meshes/rock_small.obj";

// A tetrahedron (4 vertices, 4 triangles, outward) in OBJ.
constexpr char kTetraObj[] =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";

class MeshLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::path(::testing::TempDir()) / ("vb_mesh_" + std::to_string(getpid()))).string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (fs::path(dir_) / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  void ExpectMeshError(const std::string& path, const std::string& what) const {
    test::ExpectInputError([&] { LoadMeshVertices(path, "task.yaml", 7, "obstacles.shapes.rock.mesh"); },
                           "task.yaml", 7, "obstacles.shapes.rock.mesh",
                           "mesh '" + path + "': " + what);
  }
  std::string dir_;
};

TEST_F(MeshLoaderTest, CommittedRockLoads) {
  const std::vector<Vec3> v = LoadMeshVertices(kRock, "task.yaml", 1, "k");
  ASSERT_EQ(v.size(), 12u);
  Vec3 lo = v[0], hi = v[0];
  for (const Vec3& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // data/meshes/README.md: 1.05 x 1.10 x 0.85 m
  EXPECT_NEAR(hi.x() - lo.x(), 1.05, 0.01);
  EXPECT_NEAR(hi.y() - lo.y(), 1.10, 0.01);
  EXPECT_NEAR(hi.z() - lo.z(), 0.85, 0.01);
}

TEST_F(MeshLoaderTest, StlAndGltfGiveTheSameSolid) {
  const std::string stl = Write("tetra.stl",
                                "solid t\n"
                                "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\n"
                                "vertex 1 0 0\nendloop\nendfacet\n"
                                "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                "vertex 0 0 1\nendloop\nendfacet\n"
                                "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\n"
                                "vertex 0 0 1\nendloop\nendfacet\n"
                                "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\n"
                                "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  EXPECT_EQ(LoadMeshVertices(stl, "t", 1, "k").size(), 4u);
  // glTF 2.0 with the buffer inline: 4 float32 positions (48 bytes) + 12 uint16 indices (24)
  std::string bin;
  auto put_f = [&](float f) { bin.append(reinterpret_cast<const char*>(&f), 4); };
  auto put_u16 = [&](uint16_t u) { bin.append(reinterpret_cast<const char*>(&u), 2); };
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f}) put_f(f);
  for (uint16_t u : {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2}) put_u16(u);
  static const char kB64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string b64;
  for (size_t i = 0; i < bin.size(); i += 3) {
    uint32_t n = static_cast<uint8_t>(bin[i]) << 16;
    if (i + 1 < bin.size()) n |= static_cast<uint8_t>(bin[i + 1]) << 8;
    if (i + 2 < bin.size()) n |= static_cast<uint8_t>(bin[i + 2]);
    b64 += kB64[(n >> 18) & 63];
    b64 += kB64[(n >> 12) & 63];
    b64 += i + 1 < bin.size() ? kB64[(n >> 6) & 63] : '=';
    b64 += i + 2 < bin.size() ? kB64[n & 63] : '=';
  }
  const std::string gltf = Write(
      "tetra.gltf",
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
 "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)" + b64 + R"("}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                 {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 1]},
               {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]})");
  EXPECT_EQ(LoadMeshVertices(gltf, "t", 1, "k").size(), 4u);
}

TEST_F(MeshLoaderTest, BadMeshesAreLocatedErrors) {
  ExpectMeshError((fs::path(dir_) / "missing.obj").string(), "does not exist");
  ExpectMeshError(dir_, "");   // a directory
  ExpectMeshError(Write("empty.obj", "# nothing\n"), "");
  ExpectMeshError(Write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "");
  // an open tetrahedron: one face missing, three edges on one triangle only
  ExpectMeshError(Write("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n"),
                  "non-manifold: the edge");
  // a fin: a fifth triangle on an edge of a closed tetrahedron
  ExpectMeshError(Write("fin.obj", std::string(kTetraObj) + "v 2 2 2\nf 1 2 5\n"), "non-manifold");
  // millimetres: 1000 "m" across
  ExpectMeshError(Write("mm.obj", "v 0 0 0\nv 1000 0 0\nv 0 1000 0\nv 0 0 1000\n"
                                  "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"),
                  "huge: 1000.0 m across");
  EXPECT_NO_THROW(LoadMeshVertices(Write("tetra.obj", kTetraObj), "t", 1, "k"));
}

TEST_F(MeshLoaderTest, EmptyAndHugeSayWhat) {
  try {
    LoadMeshVertices(Write("empty.obj", "# nothing\n"), "task.yaml", 3, "k");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_TRUE(msg.find("empty") != std::string::npos ||
                msg.find("cannot be read as a mesh") != std::string::npos)
        << msg;
  }
  // 110 001 distinct vertices (the limit counts merged positions, NEW-13 below).
  std::string many;
  for (int i = 0; i < 36667; ++i) {
    const std::string x = std::to_string(i);
    many += "v " + x + " 0 0\nv " + x + " 1 0\nv " + x + " 0 1\nf -3 -2 -1\n";
  }
  try {
    LoadMeshVertices(Write("many.obj", many), "task.yaml", 3, "k");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("huge: more than 100000 vertices"), std::string::npos)
        << e.what();
  }
}

// A glTF tetrahedron whose one buffer is the file `uri` (36 bytes: 4 float3 positions, then 12
// uint16 indices would follow in a real file; here the reference itself is what is tested).
std::string GltfWithBuffer(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "buffers": [{"uri": ")" + uri + R"(", "byteLength": 48}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 1]}]})";
}

TEST_F(MeshLoaderTest, ReferencedFilesAreCheckedLikeTheMeshItself) {
  // NEW-12 of the probe at 8ff4def: an OBJ's mtllib or a glTF buffer that is a FIFO blocked the
  // load forever (assimp opened it unchecked); a buffer outside the mesh's directory was read.
  const std::string fifo = (fs::path(dir_) / "cube.mtl").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string obj = Write("fifo_mtl.obj", std::string("mtllib cube.mtl\n") + kTetraObj);
  test::ExpectInputError([&] { LoadMeshVertices(obj, "task.yaml", 7, "k"); }, "task.yaml", 7,
                         "k", "cube.mtl' is a FIFO, not a regular file");
  ASSERT_EQ(::mkfifo((fs::path(dir_) / "buf.bin").c_str(), 0600), 0);
  test::ExpectInputError(
      [&] { LoadMeshVertices(Write("fifo.gltf", GltfWithBuffer("buf.bin")), "task.yaml", 7, "k"); },
      "task.yaml", 7, "k", "buf.bin' is a FIFO, not a regular file");
  test::ExpectInputError(
      [&] {
        LoadMeshVertices(Write("out.gltf", GltfWithBuffer("../../../../../../etc/passwd")),
                         "task.yaml", 7, "k");
      },
      "task.yaml", 7, "k", "is outside the mesh file's directory");
}

TEST_F(MeshLoaderTest, TheVertexLimitCountsDistinctVertices) {
  // NEW-13 of the probe at 8ff4def: a closed OBJ sphere of 25 442 vertices (4 face corners per
  // quad) was refused as "more than 100000 vertices".
  const int n = 160;
  std::string text;
  const double pi = 3.14159265358979323846;
  text += "v 0 0 1\n";
  for (int i = 1; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double t = pi * i / n, p = 2 * pi * j / n;
      text += "v " + std::to_string(std::sin(t) * std::cos(p)) + " " +
              std::to_string(std::sin(t) * std::sin(p)) + " " + std::to_string(std::cos(t)) + "\n";
    }
  }
  text += "v 0 0 -1\n";
  const int last = 2 + (n - 1) * n;
  auto k = [&](int i, int j) { return 2 + (i - 1) * n + j % n; };
  for (int j = 0; j < n; ++j) {
    text += "f 1 " + std::to_string(k(1, j)) + " " + std::to_string(k(1, j + 1)) + "\n";
    text += "f " + std::to_string(last) + " " + std::to_string(k(n - 1, j + 1)) + " " +
            std::to_string(k(n - 1, j)) + "\n";
  }
  for (int i = 1; i < n - 1; ++i) {
    for (int j = 0; j < n; ++j) {
      text += "f " + std::to_string(k(i, j)) + " " + std::to_string(k(i + 1, j)) + " " +
              std::to_string(k(i + 1, j + 1)) + " " + std::to_string(k(i, j + 1)) + "\n";
    }
  }
  EXPECT_EQ(LoadMeshVertices(Write("sphere.obj", text), "t", 1, "k").size(), 25442u);
}

}  // namespace
}  // namespace vb::io
