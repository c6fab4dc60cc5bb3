// A convex polyhedron for body-body contact (chassis envelopes, obstacles): vertices, outward
// face planes, edges, and the points vb's contact generation tests against the other shape
// (vertices plus samples along every edge). Built once; contact queries only read it.
#pragma once

#include <string>
#include <vector>

#include "vb/engine/types.h"

namespace vb::engine {

struct ConvexShape {
  struct Face {
    Vec3 normal = Vec3::UnitZ();   // outward unit normal
    double offset = 0.0;           // plane: normal . x = offset
  };
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::vector<std::pair<int, int>> edges;   // vertex indices
  // Vertices, then points every <= sample_spacing_m along each edge (ends excluded).
  std::vector<Vec3> samples;
  Vec3 aabb_min = Vec3::Zero();
  Vec3 aabb_max = Vec3::Zero();

  // Signed distance of p to the surface along the face of least penetration: > 0 outside (a lower
  // bound of the true distance), < 0 inside (minus the depth below the nearest face). *face gets
  // that face's index.
  double SignedDistance(const Vec3& p, int* face) const;
  // Whether p is strictly inside; if so, *signed_distance and *face are what SignedDistance gives
  // (bit for bit: the same faces in the same order). Stops at the first face p is not below, so
  // the contact queries, which only use inside points, skip most of the faces of a far point.
  // `hint` (optional, in/out): a face to try first, set to the face that rejected p; neighbouring
  // query points (samples along an edge) are mostly rejected by the same face.
  bool Inside(const Vec3& p, double* signed_distance, int* face, int* hint = nullptr) const;
  // The same shape moved by `pose` (vertices, planes, samples, box).
  ConvexShape Transformed(const Pose& pose) const;
  // Transformed into *out, reusing its storage (no allocation once sized). Without samples, only
  // vertices, faces, edges and the box: enough for a quick reject; TransformSamplesInto adds them.
  void TransformInto(const Pose& pose, ConvexShape* out, bool with_samples = true) const;
  void TransformSamplesInto(const Pose& pose, ConvexShape* out) const;
};

// An axis-aligned box of half extents `half_m` centred at `center` (8 vertices, 6 faces).
ConvexShape MakeBox(const Vec3& center, const Vec3& half_m, double sample_spacing_m);
// The convex hull of `points` (at least 4, not all in one plane), faces merged where coplanar.
// False with *error set if there is no such hull.
bool TryMakeConvexHull(const std::vector<Vec3>& points, double sample_spacing_m, ConvexShape* out,
                       std::string* error);
// The same, throwing InputError naming `what` if the hull is degenerate.
ConvexShape MakeConvexHull(const std::vector<Vec3>& points, double sample_spacing_m,
                           const std::string& what);
// The vertices of each face (indices into shape.vertices), counter-clockwise seen from outside,
// in face order: what a picture of the shape draws.
std::vector<std::vector<int>> FacePolygons(const ConvexShape& shape);
// Most sample points one shape may have: what a contact query may visit per step and what the
// shape holds in memory (24 bytes each). The spacing comes from input (a vehicle's wheel radius,
// a world's scale), so the count is checked before anything is allocated (NEW-4 of the probe at
// 8ff4def: a 1e-6 m wheel asked for 1e8 samples and ran out of memory).
constexpr double kMaxShapeSamples = 1 << 18;
// The number of sample points FinishShape would make (vertices + interior points of every edge),
// in floating point so that an absurd spacing cannot overflow it.
double ShapeSampleCount(const ConvexShape& shape, double sample_spacing_m);
// Adds the edge samples and the bounding box (after vertices, faces and edges are set). The
// count must be at most kMaxShapeSamples (callers check ShapeSampleCount; a hull reports it).
void FinishShape(double sample_spacing_m, ConvexShape* shape);

}  // namespace vb::engine
