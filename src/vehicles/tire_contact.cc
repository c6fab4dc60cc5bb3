#include "vb/vehicles/tire_contact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "vb/engine/exact_round.h"

namespace vb::vehicles {

namespace {

// Slices across the tread (tread edges, quarter points, centre) and their weights: the composite
// trapezoid rule of the line load over the width (weights sum to 1, so on even ground the
// resultant penetration is the mean over the width, as the line load it replaces).
constexpr int kSlices = 5;
constexpr double kSliceWeight[kSlices] = {0.125, 0.25, 0.25, 0.25, 0.125};
// The terrain section under a slice is piecewise linear with a kink wherever the line crosses a
// grid line or a cell's SW-NE diagonal: those crossings within +-r (plus the two ends) are its
// exact vertices (~6 on the benchmark's 1 m grid). Fine grids (test worlds) with more crossings
// than this fall back to uniform samples 2r / (kMaxSamples - 1) apart.
constexpr int kMaxSamples = 256;
// Smallest cosine of the wheel plane's tilt from vertical used to map vertical depth into the
// wheel plane (a wheel lying nearly flat: 87 deg).
constexpr double kMinCosTilt = 0.05;

// What SectionVertices needs of the terrain and the rolling direction: the same for a wheel's
// five slices.
struct SectionFrame {
  double inv_dx, inv_dy, du, dv, pu_scale, pv_scale, half_x, half_y;
  double dw[5];
};

SectionFrame MakeSectionFrame(const terrain::Terrain& terrain, const Vec3& fwd) {
  SectionFrame f;
  f.inv_dx = 1.0 / terrain.spacing_x_m();
  f.inv_dy = 1.0 / terrain.spacing_y_m();
  f.du = fwd.x() * f.inv_dx;
  f.dv = -fwd.y() * f.inv_dy;
  // patch grid coordinates (as Terrain::PatchIndex)
  f.pu_scale = terrain.patches().cols / terrain.size_x_m();
  f.pv_scale = terrain.patches().rows / terrain.size_y_m();
  f.half_x = 0.5 * terrain.size_x_m();
  f.half_y = 0.5 * terrain.size_y_m();
  const double dw[5] = {f.du, f.dv, f.du + f.dv, fwd.x() * f.pu_scale, -fwd.y() * f.pv_scale};
  for (int k = 0; k < 5; ++k) f.dw[k] = dw[k];
  return f;
}

// Positions a (ascending, from -r to r) along q0 + a fwd where the terrain section has a vertex:
// the ends and every crossing of a grid line (u or v integral) or a cell diagonal (u + v
// integral; grid coordinates as in Terrain); with `seams`, also every crossing of a patch
// boundary (where the material, and so soil or rigid, may change). Returns their count.
int SectionVertices(const SectionFrame& fr, const Vec3& q0, double r, bool seams,
                    std::array<double, kMaxSamples>* a) {
  const double u0 = (q0.x() + fr.half_x) * fr.inv_dx;
  const double v0 = (fr.half_y - q0.y()) * fr.inv_dy;
  const double w0[5] = {u0, v0, u0 + v0, (q0.x() + fr.half_x) * fr.pu_scale,
                        (fr.half_y - q0.y()) * fr.pv_scale};
  const double* dw = fr.dw;
  const int families = seams ? 5 : 3;
  int count = 0;
  (*a)[count++] = -r;
  for (int f = 0; f < families; ++f) {
    if (std::abs(dw[f]) * r < 1e-9) continue;
    const double lo = w0[f] - r * std::abs(dw[f]), hi = w0[f] + r * std::abs(dw[f]);
    const double first = FloorExact(lo) + 1.0, last = CeilExact(hi) - 1.0;
    if (count + (last - first + 1.0) > kMaxSamples - 1) {  // too fine: uniform samples
      const int n = kMaxSamples;
      for (int j = 0; j < n; ++j) (*a)[j] = -r + 2.0 * r * j / (n - 1);
      return n;
    }
    for (double m = first; m <= last; m += 1.0) (*a)[count++] = (m - w0[f]) / dw[f];
  }
  // ascending: std::sort of up to 16 elements is libstdc++'s insertion sort (stable); the same
  // here without the calls, std::sort beyond
  double* const first = a->data() + 1;
  const int n_sort = count - 1;
  if (n_sort > 16) {
    std::sort(first, first + n_sort);
  } else {
    for (int i = 1; i < n_sort; ++i) {
      const double v = first[i];
      int j = i;
      for (; j > 0 && v < first[j - 1]; --j) first[j] = first[j - 1];
      first[j] = v;
    }
  }
  (*a)[count++] = r;
  // drop coincident crossings (a grid vertex is on all three families): no empty segments
  int kept = 1;
  for (int j = 1; j < count; ++j) {
    if ((*a)[j] - (*a)[kept - 1] > 1e-9 * r) (*a)[kept++] = (*a)[j];
  }
  (*a)[kept - 1] = r;
  return kept;
}

}  // namespace

// The wheel is a cylinder (radius r, width w). Each of kSlices circles across its width is
// intersected with the terrain surface in the wheel's plane: the section of the triangulated
// height grid is a polyline, sampled within +-r of the centre. Every feature of that polyline
// inside the circle is a contact: a face (the perpendicular from the centre falls inside a
// segment: the terrain's normal there, penetration along it) or a convex corner (the closest
// point is a vertex, e.g. the edge of a step or a crest: normal from the corner to the wheel
// centre). So the wheel feels a rising face ahead of its lowest point, and a step's edge pushes it
// up and back as a cylinder against the triangles would. The contacts' penalty forces (unit
// stiffness, weighted per slice) are summed into one resultant: its direction is the contact
// normal, its magnitude the equivalent penetration, the point the force-weighted centroid; the
// tangential (bristle) force then acts in the plane normal to the resultant, so the static-friction
// guarantees of one bristle per wheel are kept. On even ground there is one face contact per
// slice and the resultant is the line load on the lowest generatrix.
ContactGeometry FindWheelContact(const terrain::Terrain& terrain, const Vec3& c_W,
                                 const Vec3& axis_W, double radius_m, double width_m,
                                 GroundScope scope) {
  const bool rigid_only = scope == GroundScope::kRigidOnly;
  ContactGeometry out;
  Vec3 fwd = axis_W.cross(Vec3::UnitZ());  // rolling direction, horizontal
  const double fwd_len = fwd.norm();
  if (fwd_len < 1e-6) return out;  // wheel lying flat on the ground: no rolling contact
  fwd /= fwd_len;
  const Vec3 up_w = fwd.cross(axis_W);  // in the wheel plane, tilted by the camber from vertical
  const double cos_tilt = std::max(kMinCosTilt, up_w.z());
  const Vec3 down_w = -up_w;
  const double r = radius_m;
  std::array<double, kMaxSamples> a, b;  // section in the wheel plane: along fwd, depth along down
  std::array<Vec3, kMaxSamples> p3;      // the same points on the terrain, world frame
  std::array<bool, kMaxSamples> rigid;   // segment j (points j, j + 1) is rigid ground
  rigid.fill(true);
  Vec3 force = Vec3::Zero(), moment_point = Vec3::Zero();
  double weight_sum = 0.0, friction_sum = 0.0, deepest = 0.0;
  const double half_w = 0.5 * width_m;
  // The query points are shifted sideways to where the tilted wheel plane is at the circle's
  // bottom depth, so that a cambered wheel samples the ground under its own tread.
  const Vec3 lateral_shift(r * down_w.x(), r * down_w.y(), 0.0);
  const SectionFrame frame = MakeSectionFrame(terrain, fwd);
  for (int k = 0; k < kSlices; ++k) {
    const Vec3 cs = c_W + (-half_w + width_m * k / (kSlices - 1)) * axis_W;
    const int n = SectionVertices(frame, cs + lateral_shift, r, rigid_only, &a);
    double b_min = 1e300;
    for (int j = 0; j < n; ++j) {
      const Vec3 q = cs + a[j] * fwd + lateral_shift;
      const double h = terrain.Height(q.x(), q.y());
      p3[j] = Vec3(q.x(), q.y(), h);
      b[j] = (cs.z() - h) / cos_tilt;
      b_min = std::min(b_min, b[j]);
    }
    if (b_min >= r) continue;  // the whole section below the circle: no segment reaches it
    bool any_rigid = true;
    if (rigid_only) {  // each segment's material at its midpoint (no seam inside a segment)
      any_rigid = false;
      for (int j = 0; j + 1 < n; ++j) {
        const Vec3 mid = 0.5 * (p3[j] + p3[j + 1]);
        rigid[j] = !terrain::IsDeformable(terrain.SurfaceAt(mid.x(), mid.y()));
        any_rigid = any_rigid || rigid[j];
      }
    }
    if (!any_rigid) continue;  // all soil: the soil model carries this slice
    const double w_k = kSliceWeight[k];
    // material_point: where the feature's material is read (a point of the rigid side at a seam)
    auto add = [&](double qa, double qb, const Vec3& material_point, bool face) {
      const double d = std::sqrt(qa * qa + qb * qb);
      if (d >= r || d < 1e-9) return;
      // in-plane normal: from the terrain feature towards the slice centre
      const Vec3 n2 = -(qa * fwd + qb * down_w) / d;
      const terrain::SurfacePoint s = terrain.Query(material_point.x(), material_point.y());
      Vec3 nrm = n2;
      double pen = r - d;
      if (face) {  // a face: the triangle's own normal (its side slope included)
        const double c = s.normal_W.dot(n2);
        if (c <= 0.0) return;
        nrm = s.normal_W;
        pen *= c;
      }
      const double f = w_k * pen;
      force += f * nrm;
      moment_point += f * (cs + (r / d) * (qa * fwd + qb * down_w));
      weight_sum += f;
      friction_sum += f * s.friction;
      if (f > deepest) {
        deepest = f;
        out.surface = s.surface;
      }
    };
    for (int j = 0; j + 1 < n; ++j) {
      if (std::min(b[j], b[j + 1]) >= r) continue;
      const double ea = a[j + 1] - a[j], eb = b[j + 1] - b[j];
      if (rigid[j]) {
        const double t = -(a[j] * ea + b[j] * eb) / (ea * ea + eb * eb);
        if (t > 0.0 && t < 1.0) {  // the perpendicular foot inside the segment: a face
          add(a[j] + t * ea, b[j] + t * eb, p3[j] + t * (p3[j + 1] - p3[j]), true);
        }
      }
      if (j + 2 >= n || b[j + 1] >= r || !(rigid[j] || rigid[j + 1])) continue;
      const double fa = a[j + 2] - a[j + 1], fb = b[j + 2] - b[j + 1];
      if (rigid[j] && rigid[j + 1]) {
        // convex corner at vertex j + 1: closest point of both adjacent segments
        if (a[j + 1] * ea + b[j + 1] * eb <= 0.0 && a[j + 1] * fa + b[j + 1] * fb >= 0.0) {
          add(a[j + 1], b[j + 1], p3[j + 1], false);
        }
        continue;
      }
      // A seam at vertex j + 1: the rigid surface ends in an edge with a vertical face below it,
      // open towards the soil side (ahead if segment j is rigid). The edge is the closest point
      // of the face when it is below the centre (b >= 0); then it is a convex corner if it is
      // also the closest point of the rigid segment. Above the centre, the face itself is the
      // contact, if the centre is on the soil side (a rut deeper than the wheel's radius).
      const bool soil_ahead = rigid[j];
      const Vec3 rigid_mid = soil_ahead ? 0.5 * (p3[j] + p3[j + 1]) : 0.5 * (p3[j + 1] + p3[j + 2]);
      if (b[j + 1] >= 0.0) {
        const bool edge_closest = soil_ahead ? a[j + 1] * ea + b[j + 1] * eb <= 0.0
                                             : a[j + 1] * fa + b[j + 1] * fb >= 0.0;
        if (edge_closest) add(a[j + 1], b[j + 1], rigid_mid, false);
      } else if (soil_ahead ? a[j + 1] < 0.0 : a[j + 1] > 0.0) {
        add(a[j + 1], 0.0, rigid_mid, false);
      }
    }
  }
  const double f_len = force.norm();
  if (weight_sum <= 0.0 || f_len <= 0.0) return out;
  out.in_contact = true;
  out.point_W = moment_point / weight_sum;
  out.normal_W = force / f_len;
  // a wheel cannot sink more than its radius into rigid ground; beyond that the state is broken
  out.penetration_m = std::min(f_len, radius_m);
  out.patch_friction = friction_sum / weight_sum;
  return out;
}

ContactForce ComputeContactForce(const TireParams& tire, const ContactGeometry& contact,
                                 const Vec3& v_point_W, double dt, BristleState* bristle) {
  ContactForce out;
  if (!contact.in_contact) {
    bristle->deflection_W.setZero();
    return out;
  }
  const Vec3& n = contact.normal_W;

  // normal: spring-damper on penetration, compressive only
  const double v_n = v_point_W.dot(n);
  const double f_n = std::max(
      0.0, tire.normal_stiffness_npm * contact.penetration_m - tire.normal_damping_nspm * v_n);
  out.normal_force_n = f_n;

  // tangential: keep the bristle in the current tangent plane, integrate the slip
  const Vec3 v_t = v_point_W - v_n * n;
  Vec3 z = bristle->deflection_W - bristle->deflection_W.dot(n) * n;
  z += v_t * dt;

  // Coulomb limit: a bristle stretched beyond mu*Fn/k slides (its deflection is capped there)
  const double mu = std::min(tire.friction, contact.patch_friction);
  const double f_max = mu * f_n;
  const double z_max = f_max / tire.bristle_stiffness_npm;
  const double z_len = z.norm();
  if (z_len > z_max) z *= z_max / z_len;
  Vec3 f_t = -(tire.bristle_stiffness_npm * z + tire.bristle_damping_nspm * v_t);
  const double f_t_len = f_t.norm();
  if (f_t_len > f_max) f_t *= f_max / f_t_len;
  bristle->deflection_W = z;

  out.force_W = f_n * n + f_t;
  return out;
}

}  // namespace vb::vehicles
