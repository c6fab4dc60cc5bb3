// Elevation statistics of the 100 generated benchmark worlds per elevation level, next to the
// original worlds' figures (reference_verti_bench.md §9): the calibration table of
// docs/generator.md. Usage: vb_bench_generator_stats
#include <cstdio>
#include <vector>

#include "vb/terrain/generator.h"

namespace {

using vb::terrain::ElevationLevel;
using vb::terrain::ElevationStats;

struct Reference {
  const char* name;
  ElevationLevel level;
  double std_m, mean_slope_deg, p95_slope_deg, roughness_m, max_slope_deg, range_m;
};
// reference_verti_bench.md §9, per-level means over the original worlds
constexpr Reference kReference[3] = {
    {"low", ElevationLevel::kLow, 0.17, 5.4, 11.9, 0.125, 39.1, 1.82},
    {"mid", ElevationLevel::kMid, 0.32, 10.3, 22.0, 0.243, 56.2, 3.50},
    {"high", ElevationLevel::kHigh, 0.55, 16.5, 34.2, 0.410, 68.4, 5.90}};

}  // namespace

int main() {
  std::printf("command: vb_bench_generator_stats (all %d benchmark environments)\n",
              vb::terrain::kBenchmarkEnvironments);
  std::printf("| level | n | metric | vb | original | vb/original |\n|---|---|---|---|---|---|\n");
  for (const Reference& ref : kReference) {
    ElevationStats mean;
    int n = 0;
    for (int k = 0; k < vb::terrain::kBenchmarkEnvironments; ++k) {
      const vb::terrain::GeneratorOptions o = vb::terrain::BenchmarkEnvironment(k);
      if (o.elevation != ref.level) continue;
      const ElevationStats s =
          vb::terrain::ComputeElevationStats(vb::terrain::GenerateElevation(o), 1.0);
      mean.std_m += s.std_m;
      mean.mean_slope_deg += s.mean_slope_deg;
      mean.p95_slope_deg += s.p95_slope_deg;
      mean.roughness_m += s.roughness_m;
      mean.max_slope_deg += s.max_slope_deg;
      mean.range_m += s.range_m;
      ++n;
    }
    const double vb[6] = {mean.std_m / n, mean.mean_slope_deg / n, mean.p95_slope_deg / n,
                          mean.roughness_m / n, mean.max_slope_deg / n, mean.range_m / n};
    const double orig[6] = {ref.std_m, ref.mean_slope_deg, ref.p95_slope_deg, ref.roughness_m,
                            ref.max_slope_deg, ref.range_m};
    const char* names[6] = {"height std [m]", "mean slope [deg]", "p95 slope [deg]",
                            "roughness [m]", "max slope [deg]", "height range [m]"};
    for (int i = 0; i < 6; ++i) {
      std::printf("| %s | %d | %s | %.3f | %.3f | %.2f |\n", ref.name, n, names[i], vb[i], orig[i],
                  vb[i] / orig[i]);
    }
  }
  return 0;
}
