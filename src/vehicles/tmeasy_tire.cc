#include "vb/vehicles/tmeasy_tire.h"

#include <algorithm>
#include <cmath>

namespace vb::vehicles {
namespace {

// Chrono's GuessTruck80Par limit: the characteristics are not extrapolated beyond 3.5 pn.
constexpr double kMaxLoadRatio = 3.5;

SlipCurve Scaled(SlipCurve c, double mu_ratio) {
  c.fm *= mu_ratio;
  c.fs *= mu_ratio;
  c.sm *= mu_ratio;
  c.ss *= mu_ratio;
  return c;
}

}  // namespace

SlipCurve CurveAtLoad(const TmeasyDirection& a, const TmeasyDirection& b, double pn, double fz) {
  const double q = std::clamp(fz / pn, 0.0, kMaxLoadRatio);
  // through (0, 0), (pn, a), (2 pn, b): X = q (2 a - b/2 - (a - b/2) q)
  auto quadratic = [q](double x1, double x2) {
    return std::max(0.0, q * (2.0 * x1 - 0.5 * x2 - (x1 - 0.5 * x2) * q));
  };
  auto linear = [q](double x1, double x2) { return std::max(1e-4, x1 + (x2 - x1) * (q - 1.0)); };
  SlipCurve c;
  c.df0 = quadratic(a.df0, b.df0);
  c.fm = quadratic(a.fm, b.fm);
  c.fs = quadratic(a.fs, b.fs);
  c.sm = linear(a.sm, b.sm);
  c.ss = std::max(c.sm * 1.0001, linear(a.ss, b.ss));
  return c;
}

double GeneralisedForce(const SlipCurve& c, double s) {
  if (s <= 0.0 || c.fm <= 0.0) return 0.0;
  if (s <= c.sm) {
    const double sigma = s / c.sm;
    return c.df0 * s / (1.0 + sigma * (sigma + c.df0 * c.sm / c.fm - 2.0));
  }
  if (s < c.ss) {
    const double sigma = (s - c.sm) / (c.ss - c.sm);
    return c.fm - (c.fm - c.fs) * sigma * sigma * (3.0 - 2.0 * sigma);
  }
  return c.fs;
}

ContactForce ComputeTmeasyForce(const TireParams& tire, const ContactGeometry& contact,
                                const Vec3& axis_W, const Vec3& v_point_W,
                                const Vec3& v_center_W, double spin_radps, double dt,
                                TmeasyState* st) {
  ContactForce out;
  if (!contact.in_contact) {
    *st = TmeasyState();
    return out;
  }
  const Vec3& n = contact.normal_W;

  // vertical: spring-damper on the deflection of the unloaded radius, compressive only
  // (and the rim as a stiff spring once the tire has bottomed out)
  const double v_n = v_point_W.dot(n);
  const double bottomed_m =
      std::max(0.0, contact.penetration_m - (tire.unloaded_radius_m - tire.rim_radius_m));
  const double fz = std::max(0.0, tire.vertical_stiffness_npm * contact.penetration_m +
                                      tire.rim_stiffness_npm * bottomed_m -
                                      tire.vertical_damping_nspm * v_n);
  out.normal_force_n = fz;

  // contact frame: ex rolling direction, ey lateral
  Vec3 ex = axis_W.cross(n);
  if (ex.norm() < 1e-9) {
    out.force_W = fz * n;
    return out;
  }
  ex.normalize();
  const Vec3 ey = n.cross(ex);
  const double vsx = v_point_W.dot(ex), vsy = v_point_W.dot(ey);
  const double r = tire.unloaded_radius_m;
  const double v_roll = std::max(std::abs(v_center_W.dot(ex)), std::abs(spin_radps * r));

  // relaxation states (implicit in the decay term)
  st->zx = (st->zx + vsx * dt) / (1.0 + v_roll * dt / tire.relaxation_x_m);
  st->zy = (st->zy + vsy * dt) / (1.0 + v_roll * dt / tire.relaxation_y_m);
  const double sx = st->zx / tire.relaxation_x_m, sy = st->zy / tire.relaxation_y_m;

  // characteristics at this load and friction
  const double mu_ratio = contact.patch_friction / tire.mu_0;
  const SlipCurve cx =
      Scaled(CurveAtLoad(tire.x_pn, tire.x_2pn, tire.rated_load_n, fz), mu_ratio);
  const SlipCurve cy =
      Scaled(CurveAtLoad(tire.y_pn, tire.y_2pn, tire.rated_load_n, fz), mu_ratio);

  Vec3 f_t = Vec3::Zero();
  if (cx.df0 > 0.0 && cy.df0 > 0.0) {
    // combined slip: normalised slips, direction phi, combined characteristic
    const double kx = cx.fm / cx.df0, ky = cy.fm / cy.df0;
    const double hat_x = cx.sm / (cx.sm + cy.sm) + kx / (kx + ky);
    const double hat_y = cy.sm / (cx.sm + cy.sm) + ky / (kx + ky);
    const double sxn = sx / hat_x, syn = sy / hat_y;
    const double s = std::hypot(sxn, syn);
    if (s > 1e-12) {
      const double cphi = sxn / s, sphi = syn / s;
      SlipCurve c;
      c.df0 = std::hypot(cx.df0 * hat_x * cphi, cy.df0 * hat_y * sphi);
      c.fm = std::hypot(cx.fm * cphi, cy.fm * sphi);
      c.sm = std::hypot(cx.sm / hat_x * cphi, cy.sm / hat_y * sphi);
      c.fs = std::hypot(cx.fs * cphi, cy.fs * sphi);
      c.ss = std::max(c.sm * 1.0001, std::hypot(cx.ss / hat_x * cphi, cy.ss / hat_y * sphi));
      const double f = GeneralisedForce(c, s);
      f_t = -f * (cphi * ex + sphi * ey);
      // a sliding tire keeps no more deflection than the onset of sliding needs
      if (s > c.ss) {
        st->zx *= c.ss / s;
        st->zy *= c.ss / s;
      }
      // damping of the deflection state, within the peak force
      f_t -= tire.slip_damping_nspm * (vsx * ex + vsy * ey);
      const double f_max = c.fm;
      const double len = f_t.norm();
      if (len > f_max) f_t *= f_max / len;
    }
  }
  out.force_W = fz * n + f_t;

  // rolling resistance: torque against the spin, faded in over 0.1 m/s of rolling speed
  const double fade = std::clamp(spin_radps * r / 0.1, -1.0, 1.0);
  out.torque_W = -tire.rolling_resistance * fz * r * fade * axis_W;
  return out;
}

}  // namespace vb::vehicles
