// Mesh files for obstacle shapes (docs/task_format.md `obstacles.shapes`), read through assimp
// (OBJ, STL, glTF/GLB and the other formats it knows): the one place vb includes assimp. vb
// collides with the convex hull of a mesh's vertices, so the loader returns the vertices, after
// checking that the file is a usable solid:
//   - missing / not a regular file / larger than kMaxMeshFileBytes, for the mesh file and every
//     file it refers to (which must also lie in the mesh file's directory or below)
//   - not readable as a mesh (assimp's message)
//   - empty: no triangle
//   - non-manifold: an edge not shared by exactly two triangles (a hole or a fin: not a solid)
//   - huge: more than kMaxMeshVertices distinct vertices, or wider than kMaxMeshExtent_m (a mesh in
//     millimetres, not metres), or non-finite coordinates
//   - flat: its vertices span no volume
// Each is an InputError naming the task file, line and key that referred to the mesh, the mesh
// file and what is wrong; the tools exit with code 2.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/engine/types.h"

namespace vb::io {

constexpr uint64_t kMaxMeshFileBytes = 64ull << 20;
constexpr size_t kMaxMeshVertices = 100000;         // distinct positions
constexpr size_t kMaxMeshCornerVertices = 1000000;  // assimp's vertices (one per face corner)
// Every file a mesh load opens (the mesh and the files it refers to: an OBJ's mtllib, a glTF's
// buffers) must be a regular file of at most kMaxMeshFileBytes in the mesh file's directory or
// below; at most kMaxMeshFilesOpened opens and kMaxMeshReadBytes read in all.
constexpr int kMaxMeshFilesOpened = 64;
constexpr uint64_t kMaxMeshReadBytes = 4 * kMaxMeshFileBytes;
constexpr double kMaxMeshExtent_m = 100.0;

// The vertices of every mesh in the file (metres, z up, the file's own frame). referrer_file,
// line and key locate the reference in messages.
std::vector<Vec3> LoadMeshVertices(const std::string& mesh_path, const std::string& referrer_file,
                                   int line, const std::string& key);

}  // namespace vb::io
