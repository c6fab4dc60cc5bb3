#include "vb/terrain/body_contact.h"

#include <algorithm>
#include <cmath>

#include "vb/engine/exact_round.h"

namespace vb::terrain {

void ReduceContacts(const std::vector<BodyContact>& c, int max_contacts, std::vector<char>* taken,
                    std::vector<BodyContact>* out) {
  const size_t n = c.size();
  if (n == 0 || max_contacts <= 0) return;
  if (n <= static_cast<size_t>(max_contacts)) {
    out->insert(out->end(), c.begin(), c.end());
    return;
  }
  taken->assign(n, 0);
  size_t deepest = 0;
  for (size_t i = 1; i < n; ++i)
    if (c[i].depth_m > c[deepest].depth_m) deepest = i;
  const size_t first = out->size();
  (*taken)[deepest] = 1;
  out->push_back(c[deepest]);
  for (int k = 1; k < max_contacts; ++k) {
    size_t best = n;
    double best_d2 = -1.0;
    for (size_t i = 0; i < n; ++i) {
      if ((*taken)[i]) continue;
      double d2 = 1e300;
      for (size_t j = first; j < out->size(); ++j)
        d2 = std::min(d2, ((*out)[j].point_W - c[i].point_W).squaredNorm());
      if (d2 > best_d2) {
        best_d2 = d2;
        best = i;
      }
    }
    if (best == n) break;
    (*taken)[best] = 1;
    out->push_back(c[best]);
  }
}

double MaxGroundHeightUnder(const Vec3& lo, const Vec3& hi, const Terrain& ground) {
  const HeightGrid& g = ground.grid();
  const double west = -0.5 * ground.size_x_m(), north = 0.5 * ground.size_y_m();
  const double dx = ground.spacing_x_m(), dy = ground.spacing_y_m();
  const int c0 = std::max(0, static_cast<int>(FloorExact((lo.x() - west) / dx)));
  const int c1 = std::min(g.cols - 1, static_cast<int>(CeilExact((hi.x() - west) / dx)));
  const int r0 = std::max(0, static_cast<int>(FloorExact((north - hi.y()) / dy)));
  const int r1 = std::min(g.rows - 1, static_cast<int>(CeilExact((north - lo.y()) / dy)));
  // the cells covering the box (vertices one cell beyond it included): the surface is piecewise
  // linear, so its maximum over the footprint is at one of them; the centre covers a footprint
  // outside the grid (clamped heights)
  double max_h = ground.Height(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()));
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) max_h = std::max(max_h, g.At(r, c));
  return max_h;
}

bool GroundBeyondLowestFace(const engine::ConvexShape& body, const Terrain& ground) {
  // Why it is exact: every point p of the piece satisfies n.p <= offset for the lowest face
  // (n.z < 0). A ground point g inside the piece, or above one of its samples (g = p + t z,
  // t > 0), has n.g <= offset too. The ground over the footprint is made of triangles whose
  // vertices are the grid vertices below (cells covering the footprint), and n.g - offset is
  // linear on each triangle: if it is positive at every vertex it is positive everywhere.
  const engine::ConvexShape::Face* lowest = nullptr;
  for (const engine::ConvexShape::Face& f : body.faces)
    if (lowest == nullptr || f.normal.z() < lowest->normal.z()) lowest = &f;
  constexpr double kMinDownward = 0.05;  // |n.z| of a face still usable as a bottom
  if (lowest == nullptr || lowest->normal.z() > -kMinDownward) return false;
  const HeightGrid& g = ground.grid();
  const double west = -0.5 * ground.size_x_m(), north = 0.5 * ground.size_y_m();
  const double dx = ground.spacing_x_m(), dy = ground.spacing_y_m();
  const double c0 = FloorExact((body.aabb_min.x() - west) / dx);
  const double c1 = CeilExact((body.aabb_max.x() - west) / dx);
  const double r0 = FloorExact((north - body.aabb_max.y()) / dy);
  const double r1 = CeilExact((north - body.aabb_min.y()) / dy);
  // outside the grid the surface is clamped, not spanned by these vertices
  if (c0 < 0.0 || r0 < 0.0 || c1 > g.cols - 1 || r1 > g.rows - 1) return false;
  constexpr double kMargin = 1e-9;  // m: well above the rounding of posed vertices and samples
  const Vec3& n = lowest->normal;
  for (int r = static_cast<int>(r0); r <= static_cast<int>(r1); ++r) {
    for (int c = static_cast<int>(c0); c <= static_cast<int>(c1); ++c) {
      const double s = n.x() * (west + c * dx) + n.y() * (north - r * dy) + n.z() * g.At(r, c);
      if (s - lowest->offset <= kMargin) return false;
    }
  }
  return true;
}

void GroundContacts(const engine::ConvexShape& body, const Terrain& ground, double body_friction,
                    int max_contacts, ContactScratch* scratch, std::vector<BodyContact>* out) {
  GroundContacts(body, ground, MaxGroundHeightUnder(body.aabb_min, body.aabb_max, ground),
                 body_friction, max_contacts, scratch, out);
}

namespace {

// Body samples below the surface: pushed along the surface normal. sample(i, &p) gives the i-th
// sample's world position (false: it is at or above max_h, p not set).
template <typename Sample>
void SampleContacts(int n, const Sample& sample, const Terrain& ground, double body_friction,
                    std::vector<BodyContact>* cand) {
  for (int i = 0; i < n; ++i) {
    Vec3 p;
    if (!sample(i, &p)) continue;
    const double h = ground.Height(p.x(), p.y());
    if (p.z() >= h) continue;
    const SurfacePoint sp = ground.Query(p.x(), p.y());
    BodyContact k;
    k.point_W = p;
    k.normal_W = sp.normal_W;
    k.depth_m = (sp.height_m - p.z()) * sp.normal_W.z();
    k.friction = std::min(body_friction,
                          IsDeformable(sp.surface) ? kBodyOnSoilFriction : sp.friction);
    cand->push_back(k);
  }
}

// Ground vertices inside the body: pushed along the body's face of least penetration. Then the
// candidates are reduced to max_contacts.
void VertexContactsAndReduce(const engine::ConvexShape& body, const Terrain& ground,
                             double body_friction, int max_contacts, ContactScratch* scratch,
                             std::vector<BodyContact>* out) {
  std::vector<BodyContact>& cand = scratch->candidates;
  const HeightGrid& g = ground.grid();
  const double west = -0.5 * ground.size_x_m(), north = 0.5 * ground.size_y_m();
  const double dx = ground.spacing_x_m(), dy = ground.spacing_y_m();
  const int ci0 = std::max(0, static_cast<int>(CeilExact((body.aabb_min.x() - west) / dx)));
  const int ci1 =
      std::min(g.cols - 1, static_cast<int>(FloorExact((body.aabb_max.x() - west) / dx)));
  const int ri0 = std::max(0, static_cast<int>(CeilExact((north - body.aabb_max.y()) / dy)));
  const int ri1 =
      std::min(g.rows - 1, static_cast<int>(FloorExact((north - body.aabb_min.y()) / dy)));
  int hint = -1;
  for (int r = ri0; r <= ri1; ++r) {
    for (int c = ci0; c <= ci1; ++c) {
      const Vec3 v(west + c * dx, north - r * dy, g.At(r, c));
      if (v.z() <= body.aabb_min.z()) continue;
      int face = 0;
      double d = 0.0;
      if (!body.Inside(v, &d, &face, &hint)) continue;
      const engine::ConvexShape::Face& f = body.faces[static_cast<size_t>(face)];
      const SurfacePoint sp = ground.Query(v.x(), v.y());
      BodyContact k;
      k.depth_m = -d;
      k.normal_W = -f.normal;
      k.point_W = v + f.normal * k.depth_m;   // on the body's face
      k.friction = std::min(body_friction,
                            IsDeformable(sp.surface) ? kBodyOnSoilFriction : sp.friction);
      cand.push_back(k);
    }
  }
  ReduceContacts(cand, max_contacts, &scratch->taken, out);
}

}  // namespace

void GroundContacts(const engine::ConvexShape& body, const Terrain& ground, double max_h,
                    double body_friction, int max_contacts, ContactScratch* scratch,
                    std::vector<BodyContact>* out) {
  scratch->candidates.clear();
  if (body.aabb_min.z() > max_h) return;
  const std::vector<Vec3>& samples = body.samples;
  SampleContacts(
      static_cast<int>(samples.size()),
      [&](int i, Vec3* p) {
        if (samples[static_cast<size_t>(i)].z() >= max_h) return false;
        *p = samples[static_cast<size_t>(i)];
        return true;
      },
      ground, body_friction, &scratch->candidates);
  VertexContactsAndReduce(body, ground, body_friction, max_contacts, scratch, out);
}

void GroundContacts(const engine::ConvexShape& body, const std::vector<Vec3>& samples_B,
                    const Pose& pose, const Terrain& ground, double max_h, double body_friction,
                    int max_contacts, ContactScratch* scratch, std::vector<BodyContact>* out) {
  scratch->candidates.clear();
  if (body.aabb_min.z() > max_h) return;
  const Mat3 r = pose.rotation.toRotationMatrix();   // as ConvexShape::TransformSamplesInto
  SampleContacts(
      static_cast<int>(samples_B.size()),
      [&](int i, Vec3* p) {
        const Vec3& s = samples_B[static_cast<size_t>(i)];
        // the third coefficient of the same expression: Eigen computes it alone as it does
        // within the whole vector (ConvexShapeTest.PosedHeightAloneIsBitIdentical)
        if ((pose.position + r * s).z() >= max_h) return false;
        *p = pose.position + r * s;
        return true;
      },
      ground, body_friction, &scratch->candidates);
  VertexContactsAndReduce(body, ground, body_friction, max_contacts, scratch, out);
}

namespace {

// True when a face plane of `a` has every vertex of `b` at least kSeparatedBy_m outside it: the two
// convex shapes are apart (a separating plane), so no point of either is inside the other.
bool SeparatedByAFaceOf(const engine::ConvexShape& a, const engine::ConvexShape& b) {
  for (const engine::ConvexShape::Face& f : a.faces) {
    bool all_outside = true;
    for (const Vec3& v : b.vertices) {
      if (f.normal.dot(v) - f.offset < kSeparatedBy_m) {
        all_outside = false;
        break;
      }
    }
    if (all_outside) return true;
  }
  return false;
}

}  // namespace

bool MayTouchAnObstacle(const engine::ConvexShape& body, const ObstacleField& field,
                        ContactScratch* scratch) {
  field.Overlapping(body.aabb_min, body.aabb_max, &scratch->obstacles);
  for (int index : scratch->obstacles) {
    const Obstacle& o = field.obstacles()[static_cast<size_t>(index)];
    if (!SeparatedByAFaceOf(o.shape, body) && !SeparatedByAFaceOf(body, o.shape)) return true;
  }
  return false;
}

void ObstacleContacts(const engine::ConvexShape& body, const ObstacleField& field,
                      double body_friction, int max_per_obstacle, ContactScratch* scratch,
                      std::vector<BodyContact>* out) {
  ObstacleContacts(body, body.samples, Pose(), field, body_friction, max_per_obstacle, scratch,
                   out);
}

void ObstacleContacts(const engine::ConvexShape& body, const std::vector<Vec3>& samples_B,
                      const Pose& pose, const ObstacleField& field, double body_friction,
                      int max_per_obstacle, ContactScratch* scratch,
                      std::vector<BodyContact>* out) {
  const Mat3 r = pose.rotation.toRotationMatrix();
  field.Overlapping(body.aabb_min, body.aabb_max, &scratch->obstacles);
  for (int index : scratch->obstacles) {
    const Obstacle& o = field.obstacles()[static_cast<size_t>(index)];
    // boxes overlapping is common (a rotated body's box is loose); shapes touching is not
    if (SeparatedByAFaceOf(o.shape, body) || SeparatedByAFaceOf(body, o.shape)) continue;
    std::vector<BodyContact>& cand = scratch->candidates;
    cand.clear();
    const double mu = std::min(body_friction, o.friction);
    // Body samples inside the obstacle. A sample is posed (as ConvexShape::TransformSamplesInto
    // does) only if it lies in the box, in the body's frame, around the obstacle's box: one
    // outside it is outside the obstacle's box in the world by at least kPoseMargin_m, far more
    // than any rounding, so the world test below would skip it too.
    Vec3 lo_B = Vec3::Constant(1e300), hi_B = Vec3::Constant(-1e300);
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? o.shape.aabb_max.x() : o.shape.aabb_min.x(),
                        (c & 2) ? o.shape.aabb_max.y() : o.shape.aabb_min.y(),
                        (c & 4) ? o.shape.aabb_max.z() : o.shape.aabb_min.z());
      const Vec3 b = r.transpose() * (corner - pose.position);
      lo_B = lo_B.cwiseMin(b);
      hi_B = hi_B.cwiseMax(b);
    }
    lo_B.array() -= kPoseMargin_m;
    hi_B.array() += kPoseMargin_m;
    int hint = -1;
    for (const Vec3& s : samples_B) {
      if ((s.array() < lo_B.array()).any() || (s.array() > hi_B.array()).any()) continue;
      const Vec3 p = pose.position + r * s;
      if ((p.array() < o.shape.aabb_min.array()).any() ||
          (p.array() > o.shape.aabb_max.array()).any()) {
        continue;
      }
      int face = 0;
      double d = 0.0;
      if (!o.shape.Inside(p, &d, &face, &hint)) continue;
      BodyContact k;
      k.point_W = p;
      k.normal_W = o.shape.faces[static_cast<size_t>(face)].normal;
      k.depth_m = -d;
      k.friction = mu;
      k.obstacle_tag = o.tag;
      cand.push_back(k);
    }
    // Obstacle samples inside the body: runs of consecutive samples whose box misses the body's
    // are skipped whole (none of their samples would pass the box test), the others sample by
    // sample in the same order.
    hint = -1;
    for (const SampleRun& run : o.sample_runs) {
      if ((run.hi.array() < body.aabb_min.array()).any() ||
          (run.lo.array() > body.aabb_max.array()).any()) {
        continue;
      }
      for (int i = run.begin; i < run.end; ++i) {
      const Vec3& q = o.shape.samples[static_cast<size_t>(i)];
      if ((q.array() < body.aabb_min.array()).any() || (q.array() > body.aabb_max.array()).any()) {
        continue;
      }
      int face = 0;
      double d = 0.0;
      if (!body.Inside(q, &d, &face, &hint)) continue;
      const engine::ConvexShape::Face& f = body.faces[static_cast<size_t>(face)];
      BodyContact k;
      k.depth_m = -d;
      k.normal_W = -f.normal;
      k.point_W = q + f.normal * k.depth_m;
      k.friction = mu;
      k.obstacle_tag = o.tag;
      cand.push_back(k);
      }
    }
    ReduceContacts(cand, max_per_obstacle, &scratch->taken, out);
  }
}

void WheelObstacleContacts(const Vec3& c, const Vec3& a, double r, double hw,
                           const ObstacleField& field, double wheel_friction, int max_per_obstacle,
                           ContactScratch* scratch, std::vector<BodyContact>* out) {
  const Vec3 reach = Vec3::Constant(r + hw);
  // A sample inside the cylinder is within r^2 + hw^2 of its centre; (r + hw)^2 is a bound with
  // room for any rounding, so the quick reject below drops no sample the exact test keeps.
  const double reach2 = (r + hw) * (r + hw);
  field.Overlapping(c - reach, c + reach, &scratch->obstacles);
  for (int index : scratch->obstacles) {
    const Obstacle& o = field.obstacles()[static_cast<size_t>(index)];
    // The cylinder's deepest point below each obstacle face (the wheel's point furthest along the
    // face's inward normal) and how far it is outside that face. One face with the whole cylinder
    // outside it (by kSeparatedBy_m) separates them: no sample is in the cylinder and no point of
    // it in the obstacle, so the tests below would find nothing.
    const size_t nf = o.shape.faces.size();
    scratch->face_points.resize(nf);
    scratch->face_depths.resize(nf);
    bool separated = false;
    for (size_t i = 0; i < nf && !separated; ++i) {
      const engine::ConvexShape::Face& f = o.shape.faces[i];
      const double na = f.normal.dot(a);
      Vec3 in_plane = f.normal - na * a;
      const double in_norm = in_plane.norm();
      Vec3 p = c - hw * (na >= 0.0 ? 1.0 : -1.0) * a;
      if (in_norm > 1e-9) p -= r * in_plane / in_norm;
      scratch->face_points[i] = p;
      scratch->face_depths[i] = f.normal.dot(p) - f.offset;
      separated = scratch->face_depths[i] >= kSeparatedBy_m;
    }
    if (separated) continue;
    std::vector<BodyContact>& cand = scratch->candidates;
    cand.clear();
    const double mu = std::min(wheel_friction, o.friction);
    // Obstacle samples inside the cylinder push it radially, away from them: an edge under the
    // tread pushes towards the wheel centre, which is how a wheel climbs it. (A face pressed
    // against the side wall is the face case below; choosing the axial direction for samples
    // near the side walls would turn an edge across the whole tread into sideways pushes.)
    for (const Vec3& q : o.shape.samples) {
      const Vec3 u = q - c;
      if (u.squaredNorm() >= reach2) continue;
      const double along = u.dot(a);
      if (std::abs(along) >= hw) continue;
      const Vec3 radial = u - along * a;
      const double rho = radial.norm();
      if (rho >= r || rho <= 1e-9) continue;
      BodyContact k;
      k.friction = mu;
      k.obstacle_tag = o.tag;
      k.depth_m = r - rho;
      k.normal_W = -radial / rho;
      k.point_W = c + radial / rho * r + along * a;   // on the tread
      cand.push_back(k);
    }
    // The cylinder's deepest point below each obstacle face, where it lies inside the obstacle
    // with that face the least penetrated (a wheel resting on a face).
    for (size_t i = 0; i < nf; ++i) {
      const engine::ConvexShape::Face& f = o.shape.faces[i];
      const Vec3& p = scratch->face_points[i];
      // p is inside with f its least penetrated face (the first of equals) iff every other face
      // is deeper; checked face by face with an early exit (hulls have tens of faces)
      const double d = scratch->face_depths[i];
      if (d >= 0.0) continue;
      bool least = true;
      for (const engine::ConvexShape::Face& g : o.shape.faces) {
        if (&g == &f) continue;
        const double dg = g.normal.dot(p) - g.offset;
        if (dg > d || (dg == d && &g < &f)) {
          least = false;
          break;
        }
      }
      if (!least) continue;
      BodyContact k;
      k.point_W = p;
      k.normal_W = f.normal;
      k.depth_m = -d;
      k.friction = mu;
      k.obstacle_tag = o.tag;
      cand.push_back(k);
    }
    ReduceContacts(cand, max_per_obstacle, &scratch->taken, out);
  }
}

}  // namespace vb::terrain
