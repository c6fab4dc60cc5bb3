#include "vb/soil/bekker.h"

#include <algorithm>
#include <cmath>

namespace vb::soil {

namespace {

double Modulus(const SoilParams& s, double b_m) { return s.bekker_kc / b_m + s.bekker_kphi; }

// Load carried by a rigid wheel at sinkage z0, integrating the Bekker pressure over the exact
// circular rim (midpoint rule, fine enough for 1e-6 relative accuracy in the tests).
double WheelLoadExact(const SoilParams& s, double r_m, double b_m, double z0_m) {
  const double half_length = std::sqrt(std::max(0.0, r_m * r_m - (r_m - z0_m) * (r_m - z0_m)));
  constexpr int kSteps = 4000;
  const double dx = 2.0 * half_length / kSteps;
  const double k = Modulus(s, b_m);
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = -half_length + (i + 0.5) * dx;
    const double z = z0_m - (r_m - std::sqrt(r_m * r_m - x * x));
    if (z > 0.0) sum += k * std::pow(z, s.bekker_n) * dx;
  }
  return b_m * sum;
}

}  // namespace

double BekkerPressure(const SoilParams& s, double b_m, double z_m) {
  return z_m > 0.0 ? Modulus(s, b_m) * std::pow(z_m, s.bekker_n) : 0.0;
}

double PlateSinkage(const SoilParams& s, double b_m, double l_m, double load_n) {
  const double p = load_n / (b_m * l_m);
  return std::pow(p / Modulus(s, b_m), 1.0 / s.bekker_n);
}

double WheelSinkageBekker(const SoilParams& s, double r_m, double b_m, double load_n) {
  const double n = s.bekker_n;
  const double base = 3.0 * load_n / ((3.0 - n) * b_m * Modulus(s, b_m) * std::sqrt(2.0 * r_m));
  return std::pow(base, 2.0 / (2.0 * n + 1.0));
}

double WheelSinkageExact(const SoilParams& s, double r_m, double b_m, double load_n) {
  // Load grows monotonically with sinkage: bisection on [0, r].
  double lo = 0.0, hi = r_m;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (WheelLoadExact(s, r_m, b_m, mid) < load_n ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double CompactionResistance(const SoilParams& s, double b_m, double z0_m) {
  return b_m * Modulus(s, b_m) * std::pow(z0_m, s.bekker_n + 1.0) / (s.bekker_n + 1.0);
}

double DrawbarPullWong(const SoilParams& s, double r_m, double b_m, double load_n, double slip) {
  const double z0 = WheelSinkageBekker(s, r_m, b_m, load_n);  // rolling: front arc carries W
  const double l = std::sqrt(2.0 * r_m * z0);
  const double sl = slip * l;
  const double mobilised = sl > 0.0 ? 1.0 - s.janosi_shear_m / sl * (1.0 - std::exp(-sl / s.janosi_shear_m)) : 0.0;
  const double thrust =
      (b_m * l * s.cohesion_pa + load_n * std::tan(s.friction_angle_rad)) * mobilised;
  return thrust - CompactionResistance(s, b_m, z0);
}

double DrawbarPullWongTrack(const SoilParams& s, double b_m, double l_m, double load_n,
                            double slip) {
  const double z0 = PlateSinkage(s, b_m, l_m, load_n);
  const double il = slip * l_m;
  const double mobilised =
      il > 0.0 ? 1.0 - s.janosi_shear_m / il * (1.0 - std::exp(-il / s.janosi_shear_m)) : 0.0;
  const double thrust =
      (b_m * l_m * s.cohesion_pa + load_n * std::tan(s.friction_angle_rad)) * mobilised;
  return thrust - CompactionResistance(s, b_m, z0);
}

double LateralForceWong(const SoilParams& s, double r_m, double b_m, double load_n,
                        double slip_angle_rad) {
  const double z0 = WheelSinkageBekker(s, r_m, b_m, load_n);
  const double l = std::sqrt(2.0 * r_m * z0);
  const double jl = std::tan(slip_angle_rad) * l;  // side shear displacement at the rear end
  const double mobilised = jl > 0.0 ? 1.0 - s.janosi_shear_m / jl * (1.0 - std::exp(-jl / s.janosi_shear_m)) : 0.0;
  return (b_m * l * s.cohesion_pa + load_n * std::tan(s.friction_angle_rad)) * mobilised;
}

}  // namespace vb::soil
