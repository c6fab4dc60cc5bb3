// Rigid-tire / rigid-ground contact owned by vb (not Bullet): the tire is a cylinder (radius,
// width) against the triangulated terrain surface. Five circles across the tread are intersected
// with the surface in the wheel's plane; every face or convex corner of that section inside a
// circle is a contact with its own normal and penetration (so the wheel feels a rising face or a
// step's edge ahead of its lowest point, as a cylinder against the triangles does), and their
// penalty forces are summed into one resultant contact per wheel (tread centre on even ground,
// towards the lower tread edge when the wheel is tilted against the ground, e.g. on a tilt
// table; tilted back towards the wheel centre at a step).
//  - Normal: penalty spring-damper on the penetration, never pulling.
//  - Tangential: an elastic bristle (stick state) with damping, limited by Coulomb
//    |Ft| <= mu*Fn with mu = min(tire mu, patch mu) (Chrono's NSC composition; the patch mu is the
//    contacts' force-weighted mean). The bristle holds static loads exactly, so a braked vehicle
//    on a slope below atan(mu) does not creep, which a velocity-regularised Coulomb law cannot do.
#pragma once

#include "vb/engine/types.h"
#include "vb/terrain/terrain.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::vehicles {

// Where the wheel touches the ground (geometry only).
struct ContactGeometry {
  bool in_contact = false;
  Vec3 point_W = Vec3::Zero();      // on the tread: force-weighted centroid of the contacts
  Vec3 normal_W = Vec3::UnitZ();    // direction of the contacts' summed penalty force
  double penetration_m = 0.0;       // equivalent: |summed force| / stiffness, > 0 in contact
  terrain::SurfaceClass surface = terrain::SurfaceClass::kDirt;
  double patch_friction = 0.0;
};

// Finds the contact of a cylinder of radius r and width w with centre c_W and spin axis axis_W
// (unit). On even ground penetration_m is the mean penetration over the width (normal force =
// k * mean); with several contacts, the resultant of their penalty forces. Allocates nothing.
//
// GroundScope::kRigidOnly is for a wheel near a soil/rigid seam whose soil part the soil model
// carries: only the rigid patches are ground here. Their surface ends at the seam in an edge with
// a vertical face below it (the soil side is open), so a wheel sunk in a rut meets the rigid
// patch as a step to climb: the edge as a convex corner (normal from the edge to the wheel
// centre) or, with the edge above the centre, the vertical face (horizontal normal), never as the
// rigid surface's full height above the wheel's bottom.
enum class GroundScope { kAll, kRigidOnly };
ContactGeometry FindWheelContact(const terrain::Terrain& terrain, const Vec3& c_W,
                                 const Vec3& axis_W, double radius_m, double width_m,
                                 GroundScope scope = GroundScope::kAll);

// Bristle state of one contact (world-frame tangential deflection, m).
struct BristleState {
  Vec3 deflection_W = Vec3::Zero();
};

struct ContactForce {
  Vec3 force_W = Vec3::Zero();      // total force on the wheel at the contact point
  Vec3 torque_W = Vec3::Zero();     // extra torque on the wheel (rolling resistance)
  double normal_force_n = 0.0;
};

// Contact force for this step. v_point_W: velocity of the wheel material point at the contact.
// Updates the bristle state (reset when contact is lost).
ContactForce ComputeContactForce(const TireParams& tire, const ContactGeometry& contact,
                                 const Vec3& v_point_W, double dt, BristleState* bristle);

}  // namespace vb::vehicles
