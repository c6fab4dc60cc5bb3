#include "vb/vehicles/tire_contact.h"

#include <algorithm>
#include <cmath>

namespace vb::vehicles {

ContactGeometry FindWheelContact(const terrain::Terrain& terrain, const Vec3& c_W,
                                 const Vec3& axis_W, double radius_m, double width_m) {
  ContactGeometry out;

  // direction from the centre to the lowest point of the disc: the terrain's downward normal
  // projected into the wheel plane
  const Vec3 n_c = terrain.Normal(c_W.x(), c_W.y());
  Vec3 down = -(n_c - n_c.dot(axis_W) * axis_W);
  const double len = down.norm();
  if (len < 1e-6) return out;  // wheel lying flat on the ground: no rolling contact
  down /= len;

  // The cylinder's lowest generatrix: its two ends (the tread edges) and their penetration below
  // the local terrain plane, measured along the normal there. Along the width the penetration is
  // linear; the contact is the resultant of that line load: mean penetration over the width and
  // the point at its centroid (tread centre when level, towards the lower edge when tilted).
  const double half_w = 0.5 * width_m;
  const Vec3 p_mid = c_W + radius_m * down;
  const Vec3 p_minus = p_mid - half_w * axis_W, p_plus = p_mid + half_w * axis_W;
  const terrain::SurfacePoint s_minus = terrain.Query(p_minus.x(), p_minus.y());
  const terrain::SurfacePoint s_plus = terrain.Query(p_plus.x(), p_plus.y());
  const double d_minus = (s_minus.height_m - p_minus.z()) * s_minus.normal_W.z();
  const double d_plus = (s_plus.height_m - p_plus.z()) * s_plus.normal_W.z();
  if (d_minus <= 0.0 && d_plus <= 0.0) return out;

  double mean = 0.0, u = 0.0;  // mean penetration over the width; centroid offset along axis
  if (d_minus > 0.0 && d_plus > 0.0) {
    mean = 0.5 * (d_minus + d_plus);
    u = width_m / 6.0 * (d_plus - d_minus) / (d_plus + d_minus);  // trapezoid centroid
  } else {
    const double d = std::max(d_minus, d_plus);  // one edge in: a triangle of length l
    const double l = width_m * d / (d - std::min(d_minus, d_plus));
    mean = 0.5 * d * l / width_m;
    u = (d_plus > 0.0 ? 1.0 : -1.0) * (half_w - l / 3.0);
  }
  const Vec3 p_W = p_mid + u * axis_W;
  const terrain::SurfacePoint s = terrain.Query(p_W.x(), p_W.y());

  out.in_contact = true;
  out.point_W = p_W;
  out.normal_W = s.normal_W;
  // a wheel cannot sink more than its radius into rigid ground; beyond that the state is broken
  out.penetration_m = std::min(mean, radius_m);
  out.surface = s.surface;
  out.patch_friction = s.friction;
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
