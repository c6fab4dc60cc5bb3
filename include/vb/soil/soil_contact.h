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

// One track's ground run this step: a belt of width `width_m` whose bottom surface is the
// polyline through points_W[0..n) (front to rear, in the track's plane), flat across its width
// along lateral_W. velocities_W are the belt material's velocities at those points (the
// structure's velocity minus the belt speed along the run). Between two points the surface and
// the velocity are linear, and every node force is shared between the segment's two points in
// the same proportion (linear "hat" weights), so the answer is a force per point.
constexpr int kMaxTrackPoints = 16;
struct TrackSoilInput {
  int track_id = 0;                     // stable per track for the whole trial
  int n_points = 0;                     // 2 .. kMaxTrackPoints
  Vec3 points_W[kMaxTrackPoints];
  Vec3 velocities_W[kMaxTrackPoints];
  Vec3 lateral_W = Vec3::UnitY();       // unit, across the belt
  double width_m = 0.0;
  double mass_kg = 0.0;                 // the mass the track carries (stabilisation)
};

// segment_on_soil[k]: the segment from point k to k + 1 stands over deformable ground (its
// midpoint decides) and its forces are included; the vehicle's rigid contact handles the others.
struct TrackSoilOutput {
  bool segment_on_soil[kMaxTrackPoints] = {};
  Vec3 point_force_W[kMaxTrackPoints];
  double point_sinkage_m[kMaxTrackPoints] = {};   // deepest node around each point
  terrain::SurfaceClass segment_surface[kMaxTrackPoints] = {};
};

class SoilContact {
 public:
  virtual ~SoilContact() = default;
  // Force and torque of the soil on one wheel for the coming step of length dt (s).
  virtual WheelSoilOutput WheelContact(const WheelSoilInput& wheel, double dt) = 0;
  // Force of the soil on one track's ground run (TrackSoilInput). Default: no soil anywhere.
  virtual TrackSoilOutput TrackContact(const TrackSoilInput& track, double dt) {
    (void)track;
    (void)dt;
    TrackSoilOutput out;
    for (Vec3& f : out.point_force_W) f.setZero();
    return out;
  }
  // Called once per step after all wheels: settle the grid (material flow, bookkeeping).
  virtual void EndStep(double dt) = 0;
};

}  // namespace vb::soil
