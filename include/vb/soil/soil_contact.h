// The interface between deformable soil and the vehicles that drive on it. The vehicle asks the
// soil, wheel by wheel, whether the wheel stands over deformable ground and, if so, for the
// soil's force and torque on it; everywhere else the vehicle's own rigid tire model applies.
// The runner owns the soil and calls EndStep once per physics step, after every vehicle has
// synchronised (that is where material flow / bulldozing happens).
// Layering: terrain -> soil -> vehicles, so the vehicle library sees this header and the soil
// library knows nothing of vehicles.
#pragma once

#include "vb/engine/types.h"
#include "vb/terrain/surface_class.h"

namespace vb::soil {

// One wheel (or one road wheel of a track) this step, in world coordinates.
struct WheelSoilInput {
  int wheel_id = 0;                     // stable per wheel for the whole trial (shear history)
  Vec3 center_W = Vec3::Zero();
  Vec3 axis_W = Vec3::UnitY();          // spin axis, unit
  Vec3 velocity_W = Vec3::Zero();       // of the wheel centre
  Vec3 angular_velocity_W = Vec3::Zero();
  double radius_m = 0.0;
  double width_m = 0.0;
  // Mass and spin inertia the contact acts on (wheel + carrier; wheel about its axle), for the
  // implicit form of the stiff soil spring and of the shear force. 0: the solver's configured
  // defaults (SoilConfig::default_wheel_*), which describe the HMMWV wheel.
  double mass_kg = 0.0;
  double spin_inertia_kgm2 = 0.0;
};

// The soil's answer. on_soil == false: the wheel is not over deformable ground; the vehicle uses
// its rigid tire and the other fields are zero.
struct WheelSoilOutput {
  bool on_soil = false;
  Vec3 force_W = Vec3::Zero();          // resultant on the wheel, applied at the wheel centre
  Vec3 torque_W = Vec3::Zero();         // resultant moment about the wheel centre
  double normal_force_n = 0.0;
  double sinkage_m = 0.0;               // below the undisturbed soil surface
  terrain::SurfaceClass surface = terrain::SurfaceClass::kSnow;
};

class SoilContact {
 public:
  virtual ~SoilContact() = default;
  // Force and torque of the soil on one wheel for the coming step of length dt (s).
  virtual WheelSoilOutput WheelContact(const WheelSoilInput& wheel, double dt) = 0;
  // Called once per step after all wheels: settle the grid (material flow, bookkeeping).
  virtual void EndStep(double dt) = 0;
};

}  // namespace vb::soil
