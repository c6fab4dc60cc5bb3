// Closed-form terramechanics (Bekker-Wong) used to check the solver: pressure-sinkage, static
// sinkage of a rigid wheel, compaction resistance and drawbar pull vs slip (Wong, "Theory of
// Ground Vehicles", ch. 2 and 4; reference_vehicle_soil.md §2). Pure functions, SI units.
#pragma once

#include "vb/soil/soil_params.h"

namespace vb::soil {

// Bekker pressure (Pa) at sinkage z (m) under a contact patch of smaller dimension b (m).
double BekkerPressure(const SoilParams& s, double b_m, double z_m);

// Static sinkage of a flat plate b x l (m) under load W (N): W / (b l) = (Kc/b + Kphi) z^n.
double PlateSinkage(const SoilParams& s, double b_m, double l_m, double load_n);

// Sinkage of a rolling rigid wheel (radius r, width b) under load W: only the front arc is
// loaded (the soil does not rebound behind the wheel); Bekker's small-sinkage closed form: z0 = [3 W / ((3 - n) b k sqrt(2 r))]^(2 / (2 n + 1)), k = Kc/b + Kphi.
double WheelSinkageBekker(const SoilParams& s, double r_m, double b_m, double load_n);

// Static sinkage of a rigid wheel pressed straight down (both arcs loaded), without the
// small-sinkage approximation: solves W = b * integral of p(z(x)) dx over the whole circular
// contact, z(x) = z0 - (r - sqrt(r^2 - x^2)).
double WheelSinkageExact(const SoilParams& s, double r_m, double b_m, double load_n);

// Compaction resistance of a rigid wheel at sinkage z0: R_c = b k z0^(n+1) / (n + 1).
double CompactionResistance(const SoilParams& s, double b_m, double z0_m);

// Drawbar pull DP(s) = H - R_c of a rigid driven wheel at slip s in (0, 1], rolling sinkage z0
// (WheelSinkageBekker: the front arc carries the load):
// thrust H = (A c + W tan(phi)) [1 - K / (s l) (1 - exp(-s l / K))] with contact length
// l = sqrt(2 r z0) (front arc), A = b l.
double DrawbarPullWong(const SoilParams& s, double r_m, double b_m, double load_n, double slip);

// Drawbar pull of one track (contact b x l, uniform pressure, load W) at slip i in (0, 1]
// (Wong, "Theory of Ground Vehicles", ch. 2): the shear displacement grows as j = i x along the
// contact, so the thrust is H = (A c + W tan(phi)) [1 - K / (i l) (1 - exp(-i l / K))], A = b l;
// minus the compaction resistance of the plate sinkage z0 (PlateSinkage), R_c = b k z0^(n+1)/(n+1).
double DrawbarPullWongTrack(const SoilParams& s, double b_m, double l_m, double load_n,
                            double slip);

// Lateral (cornering) force of a free-rolling rigid wheel at slip angle alpha in (0, pi/2), same
// contact patch: the side shear displacement grows as j_y = x tan(alpha) along the contact, so
// F_y = (A c + W tan(phi)) [1 - K / (l tan a) (1 - exp(-l tan a / K))] (Wong, "Theory of Ground
// Vehicles", lateral force of tires on soil, shear part only: no side-wall bulldozing term).
double LateralForceWong(const SoilParams& s, double r_m, double b_m, double load_n,
                        double slip_angle_rad);

}  // namespace vb::soil
