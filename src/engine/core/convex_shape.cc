#include "vb/engine/convex_shape.h"

#include <algorithm>
#include <cmath>

#include "vb/engine/error.h"

namespace vb::engine {

double ConvexShape::SignedDistance(const Vec3& p, int* face) const {
  double best = -1e300;
  int best_face = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    const double d = faces[f].normal.dot(p) - faces[f].offset;
    if (d > best) {
      best = d;
      best_face = static_cast<int>(f);
    }
  }
  if (face != nullptr) *face = best_face;
  return best;
}

bool ConvexShape::Inside(const Vec3& p, double* signed_distance, int* face, int* hint) const {
  if (hint != nullptr && *hint >= 0 && static_cast<size_t>(*hint) < faces.size()) {
    const Face& h = faces[static_cast<size_t>(*hint)];
    if (h.normal.dot(p) - h.offset >= 0.0) return false;
  }
  double best = -1e300;
  int best_face = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    const double d = faces[f].normal.dot(p) - faces[f].offset;
    if (d >= 0.0) {   // SignedDistance would be >= d >= 0: not inside
      if (hint != nullptr) *hint = static_cast<int>(f);
      return false;
    }
    if (d > best) {
      best = d;
      best_face = static_cast<int>(f);
    }
  }
  if (faces.empty()) return false;
  *signed_distance = best;
  *face = best_face;
  return true;
}

void ConvexShape::TransformSamplesInto(const Pose& pose, ConvexShape* out) const {
  const Mat3 r = pose.rotation.toRotationMatrix();
  out->samples.resize(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) out->samples[i] = pose.position + r * samples[i];
}

void ConvexShape::TransformInto(const Pose& pose, ConvexShape* out, bool with_samples) const {
  const Mat3 r = pose.rotation.toRotationMatrix();
  out->vertices.resize(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) out->vertices[i] = pose.position + r * vertices[i];
  out->faces.resize(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    out->faces[f].normal = r * faces[f].normal;
    out->faces[f].offset = faces[f].offset + out->faces[f].normal.dot(pose.position);
  }
  out->edges = edges;
  if (with_samples) {
    TransformSamplesInto(pose, out);
  } else {
    out->samples.clear();
  }
  out->aabb_min = Vec3::Constant(1e300);
  out->aabb_max = Vec3::Constant(-1e300);
  for (const Vec3& v : out->vertices) {
    out->aabb_min = out->aabb_min.cwiseMin(v);
    out->aabb_max = out->aabb_max.cwiseMax(v);
  }
}

ConvexShape ConvexShape::Transformed(const Pose& pose) const {
  ConvexShape out;
  TransformInto(pose, &out);
  return out;
}

double ShapeSampleCount(const ConvexShape& s, double sample_spacing_m) {
  double count = static_cast<double>(s.vertices.size());
  for (const auto& [a, b] : s.edges) {
    const double n = std::ceil((s.vertices[static_cast<size_t>(b)] -
                                s.vertices[static_cast<size_t>(a)]).norm() / sample_spacing_m);
    count += std::max(0.0, n - 1.0);
  }
  return count;
}

void FinishShape(double sample_spacing_m, ConvexShape* s) {
  VB_DEMAND(sample_spacing_m > 0.0);
  VB_DEMAND(ShapeSampleCount(*s, sample_spacing_m) <= kMaxShapeSamples);
  s->samples = s->vertices;
  for (const auto& [a, b] : s->edges) {
    const Vec3 pa = s->vertices[static_cast<size_t>(a)];
    const Vec3 pb = s->vertices[static_cast<size_t>(b)];
    const int n = static_cast<int>(std::ceil((pb - pa).norm() / sample_spacing_m));
    for (int k = 1; k < n; ++k) s->samples.push_back(pa + (pb - pa) * (static_cast<double>(k) / n));
  }
  s->aabb_min = Vec3::Constant(1e300);
  s->aabb_max = Vec3::Constant(-1e300);
  for (const Vec3& v : s->vertices) {
    s->aabb_min = s->aabb_min.cwiseMin(v);
    s->aabb_max = s->aabb_max.cwiseMax(v);
  }
}

ConvexShape MakeBox(const Vec3& center, const Vec3& half_m, double sample_spacing_m) {
  ConvexShape s;
  for (int i = 0; i < 8; ++i) {
    s.vertices.push_back(center + Vec3((i & 1) ? half_m.x() : -half_m.x(),
                                       (i & 2) ? half_m.y() : -half_m.y(),
                                       (i & 4) ? half_m.z() : -half_m.z()));
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      ConvexShape::Face f;
      f.normal = Vec3::Zero();
      f.normal[axis] = sign;
      f.offset = sign * center[axis] + half_m[axis];
      s.faces.push_back(f);
    }
  }
  // the 12 edges: vertex pairs differing in exactly one bit
  for (int i = 0; i < 8; ++i) {
    for (int bit : {1, 2, 4}) {
      if ((i & bit) == 0) s.edges.push_back({i, i | bit});
    }
  }
  FinishShape(sample_spacing_m, &s);
  return s;
}

std::vector<std::vector<int>> FacePolygons(const ConvexShape& s) {
  double extent = 0.0;
  if (!s.vertices.empty()) extent = (s.aabb_max - s.aabb_min).norm();
  const double tol = 1e-6 * std::max(extent, 1e-9);
  std::vector<std::vector<int>> out;
  for (const ConvexShape::Face& f : s.faces) {
    std::vector<int> ids;
    Vec3 centre = Vec3::Zero();
    for (size_t i = 0; i < s.vertices.size(); ++i) {
      if (std::abs(f.normal.dot(s.vertices[i]) - f.offset) <= tol) {
        ids.push_back(static_cast<int>(i));
        centre += s.vertices[i];
      }
    }
    if (ids.size() < 3) {
      out.push_back({});
      continue;
    }
    centre /= static_cast<double>(ids.size());
    // an in-plane basis; angles about the outward normal increase counter-clockwise
    const Vec3 u = (s.vertices[static_cast<size_t>(ids[0])] - centre).normalized();
    const Vec3 w = f.normal.cross(u);
    std::vector<std::pair<double, int>> by_angle;
    for (int id : ids) {
      const Vec3 d = s.vertices[static_cast<size_t>(id)] - centre;
      by_angle.push_back({std::atan2(d.dot(w), d.dot(u)), id});
    }
    std::sort(by_angle.begin(), by_angle.end());
    std::vector<int> polygon;
    for (const auto& [angle, id] : by_angle) polygon.push_back(id);
    out.push_back(std::move(polygon));
  }
  return out;
}

}  // namespace vb::engine
