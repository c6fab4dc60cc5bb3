#include "io/mesh_loader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "io/yaml_strict.h"
#include "vb/engine/convex_shape.h"
#include "vb/engine/error.h"

namespace vb::io {

std::vector<Vec3> LoadMeshVertices(const std::string& mesh_path, const std::string& referrer_file,
                                   int line, const std::string& key) {
  auto fail = [&](const std::string& what) {
    throw InputError(referrer_file, line, key, "mesh '" + mesh_path + "': " + what);
  };
  const std::string problem = InputFileProblem(mesh_path, kMaxMeshFileBytes);
  if (!problem.empty()) fail(problem);

  Assimp::Importer importer;
  // Triangles only; points and lines are dropped (they bound no volume).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      mesh_path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr) fail(std::string("cannot be read as a mesh: ") + importer.GetErrorString());

  // Vertices merged by exact position (a file may split them by normal or texture coordinate),
  // and every triangle's edges counted on the merged ids.
  std::map<std::tuple<double, double, double>, int> id_of;
  std::vector<Vec3> vertices;
  std::map<std::pair<int, int>, int> edge_uses;
  size_t triangles = 0, raw_vertices = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    raw_vertices += mesh->mNumVertices;
    if (raw_vertices > kMaxMeshVertices) {
      fail("huge: more than " + std::to_string(kMaxMeshVertices) + " vertices");
    }
    std::vector<int> ids(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Vec3 q(p.x, p.y, p.z);
      if (!q.allFinite()) fail("vertex " + std::to_string(v) + " is not finite");
      auto [it, inserted] =
          id_of.emplace(std::make_tuple(q.x(), q.y(), q.z()), static_cast<int>(vertices.size()));
      if (inserted) vertices.push_back(q);
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
