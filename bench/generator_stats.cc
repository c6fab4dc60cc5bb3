// Elevation statistics of the 100 generated benchmark worlds per elevation level, next to the
// original worlds' figures (reference_verti_bench.md §9): the calibration table of
// docs/generator.md, with each level's mean and its spread over worlds [min..max].
// Usage: vb_bench_generator_stats [--csv FILE] [TASK.yaml ...]
//   --csv FILE  also write one row per world (name, level and the statistics) for analysis,
//               e.g. scripts/world_spread_effect.py
//   TASK.yaml   also the statistics of these task files' worlds (e.g. original worlds imported
//               with vb_import), one table row each, after the benchmark's
#include <algorithm>
#include <exception>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "io/task_io.h"
#include "vb/terrain/generator.h"

namespace {

using vb::terrain::ElevationLevel;
using vb::terrain::ElevationStats;

constexpr int kMetrics = 6;
const char* const kMetricNames[kMetrics] = {"height std [m]",  "mean slope [deg]",
                                            "p95 slope [deg]", "roughness [m]",
                                            "max slope [deg]", "height range [m]"};

// One metric over the worlds of a level: mean and spread [min..max].
struct Spread {
  double mean, min, max;
};

struct Reference {
  const char* name;
  ElevationLevel level;
  Spread metric[kMetrics];  // in the order of kMetricNames
};
// reference_verti_bench.md §9: mean over the original worlds of the level [min..max over worlds]
constexpr Reference kReference[3] = {
    {"low",
     ElevationLevel::kLow,
     {{0.17, 0.13, 0.22},
      {5.4, 4.5, 6.5},
      {11.9, 9.5, 15.4},
      {0.125, 0.099, 0.162},
      {39.1, 25.2, 50.4},
      {1.82, 1.28, 2.24}}},
    {"mid",
     ElevationLevel::kMid,
     {{0.32, 0.25, 0.41},
      {10.3, 8.8, 13.3},
      {22.0, 17.8, 30.1},
      {0.243, 0.196, 0.328},
      {56.2, 40.9, 68.4},
      {3.50, 2.41, 4.40}}},
    {"high",
     ElevationLevel::kHigh,
     {{0.55, 0.41, 0.74},
      {16.5, 14.1, 19.8},
      {34.2, 28.7, 42.4},
      {0.410, 0.325, 0.571},
      {68.4, 56.5, 76.6},
      {5.90, 4.08, 7.09}}}};

void Metrics(const ElevationStats& s, double out[kMetrics]) {
  const double m[kMetrics] = {s.std_m,       s.mean_slope_deg, s.p95_slope_deg,
                              s.roughness_m, s.max_slope_deg,  s.range_m};
  std::copy(m, m + kMetrics, out);
}

}  // namespace

int main(int argc, char** argv) {
  const char* csv_path = nullptr;
  std::vector<std::string> task_paths;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      csv_path = argv[++i];
    } else if (argv[i][0] != '-') {
      task_paths.emplace_back(argv[i]);
    } else {
      std::fprintf(stderr, "usage: vb_bench_generator_stats [--csv FILE] [TASK.yaml ...]\n");
      return 2;
    }
  }
  std::FILE* csv = nullptr;
  if (csv_path != nullptr) {
    csv = std::fopen(csv_path, "w");
    if (csv == nullptr) {
      std::fprintf(stderr, "vb_bench_generator_stats: cannot write %s\n", csv_path);
      return 1;
    }
    std::fprintf(csv,
                 "name,elevation,height_std_m,mean_slope_deg,p95_slope_deg,roughness_m,"
                 "max_slope_deg,height_range_m\n");
  }
  std::printf("command: vb_bench_generator_stats (all %d benchmark environments)\n",
              vb::terrain::kBenchmarkEnvironments);
  std::printf(
      "| level | n | metric | vb mean [min..max] | original mean [min..max] | vb/original mean | "
      "vb/original spread (max - min) |\n|---|---|---|---|---|---|---|\n");
  for (const Reference& ref : kReference) {
    double sum[kMetrics] = {};
    double lo[kMetrics], hi[kMetrics];
    std::fill(lo, lo + kMetrics, std::numeric_limits<double>::infinity());
    std::fill(hi, hi + kMetrics, -std::numeric_limits<double>::infinity());
    int n = 0;
    for (int k = 0; k < vb::terrain::kBenchmarkEnvironments; ++k) {
      const vb::terrain::GeneratorOptions o = vb::terrain::BenchmarkEnvironment(k);
      if (o.elevation != ref.level) continue;
      double m[kMetrics];
      Metrics(vb::terrain::ComputeElevationStats(vb::terrain::GenerateElevation(o), 1.0), m);
      for (int i = 0; i < kMetrics; ++i) {
        sum[i] += m[i];
        lo[i] = std::min(lo[i], m[i]);
        hi[i] = std::max(hi[i], m[i]);
      }
      if (csv != nullptr) {
        std::fprintf(csv, "%s,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", o.name.c_str(), ref.name, m[0],
                     m[1], m[2], m[3], m[4], m[5]);
      }
      ++n;
    }
    for (int i = 0; i < kMetrics; ++i) {
      const Spread& r = ref.metric[i];
      std::printf("| %s | %d | %s | %.3f [%.3f..%.3f] | %.3f [%.3f..%.3f] | %.2f | %.2f |\n",
                  ref.name, n, kMetricNames[i], sum[i] / n, lo[i], hi[i], r.mean, r.min, r.max,
                  sum[i] / n / r.mean, (hi[i] - lo[i]) / (r.max - r.min));
    }
  }
  if (!task_paths.empty()) {
    std::printf("\n| task | elevation | %s | %s | %s | %s | %s | %s |\n", kMetricNames[0],
                kMetricNames[1], kMetricNames[2], kMetricNames[3], kMetricNames[4],
                kMetricNames[5]);
    std::printf("|---|---|---|---|---|---|---|---|\n");
  }
  for (const std::string& path : task_paths) {
    vb::terrain::TaskSpec task;
    try {
      task = vb::io::LoadTask(path);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vb_bench_generator_stats: %s\n", e.what());
      return 2;
    }
    double m[kMetrics];
    Metrics(vb::terrain::ComputeElevationStats(task.heights,
                                               task.size_x_m / (task.heights.cols - 1)),
            m);
    const std::string level(vb::terrain::ElevationLevelName(task.labels.elevation));
    std::printf("| %s | %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", task.name.c_str(),
                level.c_str(), m[0], m[1], m[2], m[3], m[4], m[5]);
    if (csv != nullptr) {
      std::fprintf(csv, "%s,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", task.name.c_str(), level.c_str(),
                   m[0], m[1], m[2], m[3], m[4], m[5]);
    }
  }
  if (csv != nullptr && std::fclose(csv) != 0) {
    std::fprintf(stderr, "vb_bench_generator_stats: cannot write %s\n", csv_path);
    return 1;
  }
  return 0;
}
