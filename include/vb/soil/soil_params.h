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
  // belt_node_stride, optional): a track's belt presses every belt_node_stride-th node in each
  // direction, each pressed node carrying the cell of stride x stride nodes and lowering the
  // block's other nodes under the belt to its level. 1 (the default): every node, as a wheel.
  // 2: a quarter of the nodes, the M113's soil contact ~2x cheaper, but its static sinkage in
  // mud 32 % above Bekker's instead of 17 % (docs/soil.md "The belt's coarse grid").
  int belt_node_stride = 1;
  // A numerical setting of the track contact (soil file: grid.belt_shear_block, optional). 1 (the
  // default): every node by the full law, as a wheel. 2: every node under the belt keeps its own
  // normal law (so bulldozing bears as on the full grid) but the slip velocity, the Janosi shear
  // and the force split are computed once per 2 x 2 block of nodes; it passes the M113's
  // validation but saves only ~2 % of its env061 step (the belt scan, not the force law, is the
  // cost: docs/soil.md "The belt's shear blocks"). belt_node_stride 2 overrides it.
  int belt_shear_block = 1;
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
