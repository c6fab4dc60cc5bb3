// Single-wheel soil bin (the classic terramechanics rig, as Chrono's ChWheelTestRig with imposed
// slip): a rigid wheel carrying a vertical load W is free to sink, is towed at a constant speed
// and spun at the angular velocity that gives the requested driving slip s = 1 - v / (omega r).
// Measured at steady state: sinkage and drawbar pull (horizontal soil force on the wheel). With a
// slip angle the wheel's heading is turned by that angle (to the left) from the towing direction
// and the side force (the cornering force along the wheel axis) is measured as well.
// Used by the validation tests and bench/soil_bin.cc (plots in docs/img).
#pragma once

#include <vector>

#include "vb/soil/soil_params.h"
#include "vb/terrain/surface_class.h"

namespace vb::soil {

struct WheelRigSpec {
  terrain::SurfaceClass soil = terrain::SurfaceClass::kMud;
  double radius_m = 0.467;         // HMMWV wheel
  double width_m = 0.254;
  double load_n = 6100.0;          // ~ a quarter of the 2.5 t HMMWV
  double speed_mps = 1.0;          // towing speed (0: static test)
  double slip = 0.0;               // driving slip in [0, 1) (of the speed along the heading)
  double slip_angle_rad = 0.0;     // heading vs towing direction, in [0, pi/2)
  double settle_s = 1.5;           // static settling before towing starts
  double travel_m = 3.0;           // towed distance
  double average_last_m = 1.5;     // steady-state averaging window (the end of the travel)
  double step_s = 0.005;
};

struct WheelRigResult {
  double static_sinkage_m = 0.0;   // at the end of settling
  double sinkage_m = 0.0;          // mean over the averaging window
  double drawbar_pull_n = 0.0;     // mean soil force along the travel direction
  double lateral_force_n = 0.0;    // mean soil force along the wheel axis (> 0: towards the side
                                   // the wheel is turned to, i.e. against the side slip)
  double drive_torque_nm = 0.0;    // mean torque the axle must supply
  double normal_force_n = 0.0;     // mean vertical soil force
  double rut_depth_m = 0.0;        // unloaded rut depth behind the wheel (below the initial level)
  double berm_height_m = 0.0;      // highest rim deposit beside the rut
  double volume_change_m3 = 0.0;   // soil volume change (0 with flow factor 1)
  double compacted_m3 = 0.0;       // plastically compacted volume moved by bulldozing
  double max_vertical_speed_mps = 0.0;  // during the steady window (stability check)
};

// Runs the rig on a flat bin of the given soil. `config` supplies the soil and grid parameters.
WheelRigResult RunWheelRig(const SoilConfig& config, const WheelRigSpec& spec);

// `config` with shear (cohesion, friction angle) and material flow switched off: the normal-
// pressure model alone, which is what the Bekker closed forms describe.
SoilConfig PressureOnly(const SoilConfig& config);

}  // namespace vb::soil
