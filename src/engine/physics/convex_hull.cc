// Convex hulls for body-body contact shapes, through Bullet's hull computer (the only Bullet use
// outside physics_world.cc, and only at build time). Faces come out as planar n-gons; vb keeps
// their planes and the edges between faces of different planes.
#include <btBulletDynamicsCommon.h>
#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "vb/engine/convex_shape.h"
#include "vb/engine/error.h"

namespace vb::engine {

bool TryMakeConvexHull(const std::vector<Vec3>& points, double sample_spacing_m, ConvexShape* out,
                       std::string* error) {
  if (points.size() < 4) {
    *error = "a convex hull needs at least 4 points, got " + std::to_string(points.size());
    return false;
  }
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    if (!p.allFinite()) {
      *error = "non-finite point";
      return false;
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = (hi - lo).norm();
  std::vector<double> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  btConvexHullComputer hull;
  hull.compute(coords.data(), 3 * static_cast<int>(sizeof(double)), static_cast<int>(points.size()),
               0.0, 0.0);
  ConvexShape& s = *out;
  s = ConvexShape();
  for (int i = 0; i < hull.vertices.size(); ++i) {
    const btVector3& v = hull.vertices[i];
    s.vertices.emplace_back(v.x(), v.y(), v.z());
  }
  // Face planes (Newell's normal of each n-gon, outward: the hull's faces are counter-clockwise
  // seen from outside). Edge index -> face index, to find the edges between different planes.
  std::vector<int> face_of_edge(static_cast<size_t>(hull.edges.size()), -1);
  for (int f = 0; f < hull.faces.size(); ++f) {
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const btConvexHullComputer::Edge* e = first;
    Vec3 normal = Vec3::Zero(), centroid = Vec3::Zero();
    int n = 0;
    do {
      const Vec3& a = s.vertices[static_cast<size_t>(e->getSourceVertex())];
      const Vec3& b = s.vertices[static_cast<size_t>(e->getTargetVertex())];
      normal += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                     (a.x() - b.x()) * (a.y() + b.y()));
      centroid += a;
      ++n;
      face_of_edge[static_cast<size_t>(e - &hull.edges[0])] = static_cast<int>(s.faces.size());
      e = e->getNextEdgeOfFace();
    } while (e != first && n < 10000);
    if (normal.norm() <= 1e-12 * extent * extent) continue;  // sliver: no plane
    ConvexShape::Face face;
    face.normal = normal.normalized();
    face.offset = face.normal.dot(centroid / n);
    s.faces.push_back(face);
  }
  if (s.faces.size() < 4 || s.vertices.size() < 4 || !(extent > 0.0)) {
    *error = "the points span no volume (all on one plane or line)";
    return false;
  }
  // Outward check: every vertex must lie on the inner side of every face.
  for (const ConvexShape::Face& f : s.faces) {
    for (const Vec3& v : s.vertices) {
      if (f.normal.dot(v) - f.offset > 1e-6 * extent) {
        *error = "hull computation failed (inconsistent face orientation)";
        return false;
      }
    }
  }
  // Edges between faces of different planes, each once.
  std::set<std::pair<int, int>> seen;
  for (int i = 0; i < hull.edges.size(); ++i) {
    const btConvexHullComputer::Edge& e = hull.edges[i];
    const int a = e.getSourceVertex(), b = e.getTargetVertex();
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    if (seen.count(key) != 0) continue;
    seen.insert(key);
    const int f0 = face_of_edge[static_cast<size_t>(i)];
    const int f1 = face_of_edge[static_cast<size_t>(e.getReverseEdge() - &hull.edges[0])];
    if (f0 >= 0 && f1 >= 0 && f0 != f1 &&
        s.faces[static_cast<size_t>(f0)].normal.dot(s.faces[static_cast<size_t>(f1)].normal) >
            1.0 - 1e-9) {
      continue;  // between two coplanar pieces of one face
    }
    s.edges.push_back(key);
  }
  const double samples = ShapeSampleCount(s, sample_spacing_m);
  if (!(samples <= kMaxShapeSamples)) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), "sampled every %.3g m for contact, its edges would give %.3g "
                  "points, more than the limit of %.0f", sample_spacing_m, samples,
                  kMaxShapeSamples);
    *error = buf;
    return false;
  }
  FinishShape(sample_spacing_m, &s);
  return true;
}

ConvexShape MakeConvexHull(const std::vector<Vec3>& points, double sample_spacing_m,
                           const std::string& what) {
  ConvexShape s;
  std::string error;
  if (!TryMakeConvexHull(points, sample_spacing_m, &s, &error)) throw InputError("", 0, what, error);
  return s;
}

}  // namespace vb::engine
