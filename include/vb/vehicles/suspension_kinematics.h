// Kinematics of a reduced double-wishbone suspension (Chrono's ChDoubleWishboneReduced topology):
// the upright is held by five distance links to the chassis (upper arm front/back, lower arm
// front/back, tie rod) and carries the spindle. vb's multibody tree cannot close these loops, so
// the vehicle keeps a vertical slider + steering knuckle per wheel and takes from this solver
// what the linkage decides: the shock length as a function of wheel travel (motion ratio, i.e. the
// wheel rate) and the road-wheel angle as a function of rack travel (steering kinematics,
// inner/outer angles). Solved once at vehicle build time into tables.
#pragma once

#include <vector>

#include "vb/engine/types.h"

namespace vb::vehicles {

// Hard points of the LEFT side in the suspension (axle) frame, metres; the right side mirrors y.
// All points marked (u) move with the upright, the others are fixed on the chassis; tierod_c is
// the inner tie-rod point, which the steering rack moves along y.
struct DoubleWishboneHardpoints {
  Vec3 spindle = Vec3::Zero();   // (u) wheel centre
  Vec3 uca_f = Vec3::Zero();
  Vec3 uca_b = Vec3::Zero();
  Vec3 uca_u = Vec3::Zero();     // (u)
  Vec3 lca_f = Vec3::Zero();
  Vec3 lca_b = Vec3::Zero();
  Vec3 lca_u = Vec3::Zero();     // (u)
  Vec3 shock_c = Vec3::Zero();
  Vec3 shock_u = Vec3::Zero();   // (u)
  Vec3 tierod_c = Vec3::Zero();
  Vec3 tierod_u = Vec3::Zero();  // (u)
};

struct UprightSolution {
  bool ok = false;               // Newton converged
  Vec3 spindle = Vec3::Zero();
  double shock_length_m = 0.0;
  double steer_angle_rad = 0.0;  // rotation of the spin axis about z (+ = toe to the left)
  double camber_rad = 0.0;       // tilt of the spin axis out of the ground plane
};

// Pose of the upright for a spindle displaced by travel_m along z (+ = bump) and the inner
// tie-rod point displaced by rack_m along y. Newton on the 6 pose unknowns (5 link lengths + the
// spindle height), continued from the design pose in sub-steps.
UprightSolution SolveDoubleWishbone(const DoubleWishboneHardpoints& hp, double travel_m,
                                    double rack_m);

// Uniformly sampled table y(x), linear interpolation, clamped at the ends.
struct Table1D {
  double x0 = 0.0;
  double dx = 1.0;
  std::vector<double> y;
  double operator()(double x) const;
  double Slope(double x) const;  // dy/dx of the segment containing x
};

// Shock length vs wheel travel over [lo, hi] (n samples) at zero rack travel.
Table1D ShockLengthTable(const DoubleWishboneHardpoints& hp, double lo_m, double hi_m, int n);
// Road-wheel angle of the LEFT wheel vs rack travel over [-rack_max, rack_max] at zero travel.
// Throws std::runtime_error if the linkage does not assemble somewhere on the way.
constexpr int kSteerAngleTableSamples = 41;   // the vehicle's table (the loader checks the same)
Table1D SteerAngleTable(const DoubleWishboneHardpoints& hp, double rack_max_m, int n);

}  // namespace vb::vehicles
