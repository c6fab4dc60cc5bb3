// TMeasy-style handling tire (after Hirschberg, Rill, Weinfurter; the model Chrono's ChTMeasyTire
// implements), written for vb's 5 ms step:
//  - vertical: linear spring-damper on the deflection of the unloaded radius, and a stiff rim
//    contact once the tire has bottomed out (deflection > unloaded radius - rim radius);
//  - longitudinal/lateral: combined-slip generalised force curve F(s) (initial slope dF0, peak FM
//    at sM, sliding FS from sS on), each characteristic given at the rated load pn and at 2 pn
//    and interpolated in load (forces and stiffnesses quadratically through (0, 0), slips
//    linearly) - the degressive load dependence of a real tire;
//  - friction combination: the curves were measured at mu_0; on a terrain patch of friction mu
//    the force maxima FM, FS and the slips sM, sS scale by mu / mu_0 (initial stiffness
//    unchanged) - Chrono scales its TMeasy forces by the same ratio;
//  - low speed / stability at 5 ms: the slip is not v_slip / v (singular at rest, and explicitly
//    unstable for the wheel's small spin inertia) but a first-order relaxation state per direction,
//    dz/dt = v_slip - (v_roll / sigma) z, s = z / sigma. At speed s tends to v_slip / v_roll
//    (TMeasy's slip); at rest z is an elastic deflection of stiffness dF0 / sigma, so a parked
//    tire holds static loads up to FM without creeping;
//  - rolling resistance torque rr * Fz * r opposing the wheel spin.
#pragma once

#include "vb/engine/types.h"
#include "vb/vehicles/tire_contact.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// One direction's characteristic at a load (N, N/unit slip, unit slip).
struct SlipCurve {
  double df0 = 0.0;
  double fm = 0.0;
  double sm = 0.0;
  double fs = 0.0;
  double ss = 0.0;
};

// Characteristic at vertical load fz, from the values at pn and 2 pn.
SlipCurve CurveAtLoad(const TmeasyDirection& at_pn, const TmeasyDirection& at_2pn, double pn,
                      double fz);

// Generalised TMeasy force magnitude for a combined slip magnitude s >= 0.
double GeneralisedForce(const SlipCurve& c, double s);

// Relaxation state of one tire (contact-frame longitudinal and lateral, m).
struct TmeasyState {
  double zx = 0.0;
  double zy = 0.0;
};

// Force (at contact.point_W) and rolling-resistance torque on the wheel for this step.
// v_point_W: velocity of the wheel material point at the contact; v_center_W: wheel centre
// velocity; spin_radps: wheel spin about axis_W.
ContactForce ComputeTmeasyForce(const TireParams& tire, const ContactGeometry& contact,
                                const Vec3& axis_W, const Vec3& v_point_W,
                                const Vec3& v_center_W, double spin_radps, double dt,
                                TmeasyState* state);

}  // namespace vb::vehicles
