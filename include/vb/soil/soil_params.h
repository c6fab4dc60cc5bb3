// Parameters of the Soil Contact Model (SCM), as plain data. Loaded in one strict place
// (tools/io/soil_io.h from data/soils/*.yaml); nothing here has a default that stands for a soil.
// Units follow the Bekker-Wong convention: pressure p = (Kc / b + Kphi) * z^n with p in Pa,
// z and b in m, so Kc is in N/m^(n+1) and Kphi in N/m^(n+2).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "vb/terrain/surface_class.h"

namespace vb::soil {

// One soil (Chrono's SetSoilParameters argument list, reference_vehicle_soil.md §2.3).
struct SoilParams {
  double bekker_kphi = 0.0;              // frictional modulus, N/m^(n+2)
  double bekker_kc = 0.0;                // cohesive modulus, N/m^(n+1)
  double bekker_n = 1.0;                 // sinkage exponent
  double cohesion_pa = 0.0;              // Mohr-Coulomb cohesion
  double friction_angle_rad = 0.0;       // Mohr-Coulomb internal friction angle
  double janosi_shear_m = 0.01;          // Janosi-Hanamoto shear deformation modulus K
  double elastic_stiffness_papm = 0.0;   // unloading/reloading stiffness Ke (stored >= Kphi)
  double damping_paspm = 0.0;            // normal viscous damping R
};

// Material flow of displaced soil to the rut rim (Chrono's SetBulldozingParameters).
struct BulldozingParams {
  bool enabled = false;
  double erosion_angle_rad = 0.0;   // slopes steeper than this flow downhill
  double flow_factor = 1.0;         // displaced volume x flow_factor goes to the rim (1: conserve)
  int erosion_iterations = 0;       // smoothing passes per step
  int erosion_propagations = 0;     // rings (4-neighbour dilations) of the smoothing domain
};

// Everything the solver needs: grid, per-class soils, bulldozing and the stabilisation mass.
struct SoilConfig {
  std::string source;                   // file it was loaded from (provenance, messages)
  double grid_spacing_m = 0.0;          // node spacing of the height grid
  // A numerical setting of the track contact, not a soil property (soil file: grid.
  // belt_node_stride, optional; the shipped verti_bench.yaml sets 2). 1 (absent): a track's belt
  // presses every node, as a wheel. 2: every second node in each direction, each carrying the
  // cell of its 2 x 2 block; the block's other nodes under the belt follow it, or, standing above
  // its level (a deposit), are pressed by their own law and bear on their own cells
  // (docs/soil.md "The belt's coarse grid"): the M113's env061 step 321.6 k -> ~287 k
  // instructions, its validation as on the full grid.
  int belt_node_stride = 1;
  // Soil per deformable class, indexed by SoilSlot(class); empty = class not described.
  std::array<std::optional<SoilParams>, 3> classes;
  BulldozingParams bulldozing;
  // Mass the wheel's contact spring acts on, for the implicit (backward-Euler) form of the stiff
  // elastic soil spring and of the shear force; used when WheelSoilInput::mass_kg is 0.
  double default_wheel_mass_kg = 0.0;
  // Spin inertia about the axle, for the tangential effective mass; used when the input gives 0.
  double default_wheel_spin_inertia_kgm2 = 0.0;

  const SoilParams* For(terrain::SurfaceClass c) const;
};

// 0 mud, 1 sand, 2 snow; -1 for rigid classes.
int SoilSlot(terrain::SurfaceClass c);

}  // namespace vb::soil
