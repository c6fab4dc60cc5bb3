#include "vb/vehicles/suspension_forces.h"

#include <algorithm>
#include <cmath>

namespace vb::vehicles {
namespace {
constexpr double kAirPolytropic = 1.4;  // adiabatic air
}  // namespace

double SpringForce(const SuspensionParams& su, double length_m) {
  switch (su.spring_law) {
    case SpringLaw::kLinear:
      return su.spring_stiffness_npm * (su.spring_free_length_m - length_m);
    case SpringLaw::kProgressive: {
      const double x = su.spring_free_length_m - length_m;
      if (x <= 0.0) return 0.0;
      return su.spring_stiffness_npm * x + su.spring_k2_npm2 * x * x;
    }
    case SpringLaw::kAir: {
      const double h = kAirPolytropic * su.spring_preload_n / su.spring_stiffness_npm;
      const double x = std::min(su.spring_design_length_m - length_m, 0.9 * h);
      return su.spring_preload_n * std::pow(h / (h - x), kAirPolytropic);
    }
  }
  return 0.0;
}

double DamperSecant(const SuspensionParams& su, double length_rate_mps) {
  const bool expanding = length_rate_mps > 0.0;
  const double c = expanding ? su.damping_expansion_nspm : su.damping_nspm;
  const double d = expanding ? su.degression_expansion_spm : su.degression_compression_spm;
  return c / (1.0 + d * std::abs(length_rate_mps));
}

double DamperForce(const SuspensionParams& su, double length_rate_mps) {
  return -DamperSecant(su, length_rate_mps) * length_rate_mps;
}

}  // namespace vb::vehicles
