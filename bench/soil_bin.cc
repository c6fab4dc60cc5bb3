// Soil bin figures and solver scaling.
//  1. Drawbar pull and sinkage vs slip of the HMMWV wheel (r 0.467 m, b 0.254 m, 6.1 kN, towed at
//     1 m/s) on the original's snow, mud and sand, against the Bekker-Wong closed forms; plots
//     written to OUT_DIR/soil_drawbar_pull.png and OUT_DIR/soil_sinkage.png.
//  2. Cost per step of the solver vs grid spacing and vs the number of wheels (N rigid wheels
//     side by side, each pressed by 6.1 kN and driven at 20 % slip over fresh mud).
//
// usage: vb_bench_soil_bin [OUT_DIR]   (default: <source>/docs/img)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "io/plot_png.h"
#include "io/soil_io.h"
#include "vb/soil/bekker.h"
#include "vb/soil/scm_soil.h"
#include "vb/soil/wheel_rig.h"
#include "vb/terrain/terrain.h"

namespace {

using vb::terrain::SurfaceClass;

const char* Name(SurfaceClass c) {
  return c == SurfaceClass::kSnow ? "snow" : c == SurfaceClass::kMud ? "mud" : "sand";
}

vb::terrain::TaskSpec Bin(double size_m, SurfaceClass c) {
  vb::terrain::TaskSpec t;
  t.name = "bin";
  t.size_x_m = t.size_y_m = size_m;
  const int n = static_cast<int>(size_m) + 1;
  t.heights.rows = t.heights.cols = n;
  t.heights.heights_m.assign(static_cast<size_t>(n) * n, 0.0);
  t.max_height_m = 1.0;
  t.patches.rows = t.patches.cols = 16;
  t.patches.classes.assign(256, c);
  t.patches.friction.assign(256, 0.0);
  return t;
}

// N wheels side by side, free vertically (semi-implicit Euler), towed at 1 m/s with 20 % slip.
// Returns microseconds of solver time per step over the towed part (median of 3 runs).
double CostPerStep_us(const vb::soil::SoilConfig& config, int wheels, long* nodes_per_step) {
  std::vector<double> runs;
  for (int rep = 0; rep < 3; ++rep) {
    const vb::terrain::TaskSpec task = Bin(32.0, SurfaceClass::kMud);
    const vb::terrain::Terrain ground(task);
    vb::soil::ScmSoil soil(ground, config);
    const double dt = 0.005, r = 0.467, load = 6100.0, mass = load / vb::kGravity;
    std::vector<double> z(wheels, r + 0.002), vz(wheels, 0.0);
    double x = -10.0;
    double seconds = 0.0;
    long steps = 0, nodes0 = 0;
    for (int k = 0; k < 1400; ++k) {
      const bool towing = k >= 400;
      const double v = towing ? 1.0 : 0.0;
      const auto t0 = std::chrono::steady_clock::now();
      for (int w = 0; w < wheels; ++w) {
        vb::soil::WheelSoilInput in;
        in.wheel_id = w;
        in.center_W = vb::Vec3(x, -0.9 * (wheels - 1) + 1.8 * w, z[w]);
        in.axis_W = vb::Vec3::UnitY();
        in.velocity_W = vb::Vec3(v, 0.0, vz[w]);
        in.angular_velocity_W = vb::Vec3(0.0, v / (r * 0.8), 0.0);
        in.radius_m = r;
        in.width_m = 0.254;
        in.mass_kg = mass;
        const vb::soil::WheelSoilOutput out = soil.WheelContact(in, dt);
        const double ramp = std::min(1.0, (k + 1) / 300.0);
        vz[w] += dt * (out.force_W.z() - ramp * load) / mass;
        z[w] += dt * vz[w];
      }
      soil.EndStep(dt);
      const auto t1 = std::chrono::steady_clock::now();
      x += dt * v;
      if (k == 400) nodes0 = soil.stats().contact_nodes;
      if (towing) {
        seconds += std::chrono::duration<double>(t1 - t0).count();
        ++steps;
      }
    }
    *nodes_per_step = (soil.stats().contact_nodes - nodes0) / std::max(1L, steps);
    runs.push_back(1e6 * seconds / steps);
  }
  std::sort(runs.begin(), runs.end());
  return runs[1];
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out_dir = argc > 1 ? argv[1] : VB_SOURCE_DIR "/docs/img";
  try {
    const vb::soil::SoilConfig config =
        vb::io::LoadSoil(VB_SOURCE_DIR "/data/soils/verti_bench.yaml");
    const double r = 0.467, b = 0.254, w = 6100.0;
    const std::vector<double> slips = {0.0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
    vb::io::LinePlot dp_plot, sink_plot;
    dp_plot.title = "HMMWV wheel (r 0.467 m, b 0.254 m, 6.1 kN) in the soil bin: drawbar pull";
    dp_plot.x_label = "slip";
    dp_plot.y_label = "drawbar pull (N)";
    sink_plot.title = "HMMWV wheel in the soil bin: sinkage (full model towed at 1 m/s)";
    sink_plot.x_label = "slip";
    sink_plot.y_label = "sinkage (m)";
    std::printf("soil  slip   DP_N   Wong_N  sinkage_m  Bekker_rolling_m  rut_m  berm_m\n");
    for (SurfaceClass c : {SurfaceClass::kSnow, SurfaceClass::kMud, SurfaceClass::kSand}) {
      const vb::soil::SoilParams& s = *config.For(c);
      vb::io::PlotSeries dp{std::string(Name(c)) + " vb", {}, {}, true};
      vb::io::PlotSeries wong{std::string(Name(c)) + " Wong", {}, {}, false};
      vb::io::PlotSeries sink{std::string(Name(c)) + " vb", {}, {}, true};
      vb::io::PlotSeries bekker{std::string(Name(c)) + " Bekker", {}, {}, false};
      // The pressure model alone (no shear, no flow) towed slowly: what Bekker's formula describes.
      vb::io::PlotSeries plain_sink{std::string(Name(c)) + " vb p-only", {}, {}, false};
      const vb::soil::SoilConfig plain = vb::soil::PressureOnly(config);
      vb::soil::WheelRigSpec plain_spec;
      plain_spec.soil = c;
      plain_spec.speed_mps = 0.1;
      const double plain_z = vb::soil::RunWheelRig(plain, plain_spec).sinkage_m;
      for (double slip : slips) {
        vb::soil::WheelRigSpec spec;
        spec.soil = c;
        spec.slip = slip;
        const vb::soil::WheelRigResult res = vb::soil::RunWheelRig(config, spec);
        const double wong_n = vb::soil::DrawbarPullWong(s, r, b, w, std::max(slip, 1e-3));
        const double z_b = vb::soil::WheelSinkageBekker(s, r, b, w);
        std::printf("%-5s %4.2f %7.1f %7.1f %10.4f %17.4f %6.4f %7.4f\n", Name(c), slip,
                    res.drawbar_pull_n, wong_n, res.sinkage_m, z_b, res.rut_depth_m, res.berm_height_m);
        dp.x.push_back(slip);
        dp.y.push_back(res.drawbar_pull_n);
        wong.x.push_back(slip);
        // At zero slip the closed form has no thrust: DP = -R_c.
        wong.y.push_back(slip > 0.0 ? wong_n : -vb::soil::CompactionResistance(s, b, z_b));
        sink.x.push_back(slip);
        sink.y.push_back(res.sinkage_m);
        bekker.x.push_back(slip);
        bekker.y.push_back(z_b);
        plain_sink.x.push_back(slip);
        plain_sink.y.push_back(plain_z);
      }
      dp_plot.series.push_back(dp);
      dp_plot.series.push_back(wong);
      sink_plot.series.push_back(sink);
      sink_plot.series.push_back(bekker);
      sink_plot.series.push_back(plain_sink);
    }
    vb::io::WriteLinePlot(dp_plot, out_dir + "/soil_drawbar_pull.png");
    vb::io::WriteLinePlot(sink_plot, out_dir + "/soil_sinkage.png");
    std::printf("plots: %s/soil_drawbar_pull.png, %s/soil_sinkage.png\n\n", out_dir.c_str(),
                out_dir.c_str());

    // Grid convergence: static sinkage of the pressure-only model (no shear, no flow) and the
    // full model's drawbar pull at 40 % slip, per grid spacing.
    std::printf("grid convergence (static sinkage: pressure only, vs exact Bekker; DP at s = 0.4: "
                "full model):\n");
    std::printf("soil  grid_m  static_m  Bekker_m  err_%%  DP_0.4_N\n");
    for (SurfaceClass c : {SurfaceClass::kSnow, SurfaceClass::kMud, SurfaceClass::kSand}) {
      for (double spacing : {0.1, 0.05, 0.025}) {
        vb::soil::SoilConfig plain = vb::soil::PressureOnly(config);
        plain.grid_spacing_m = spacing;
        vb::soil::WheelRigSpec spec;
        spec.soil = c;
        spec.speed_mps = 0.0;
        const double z = vb::soil::RunWheelRig(plain, spec).static_sinkage_m;
        const double z_exact = vb::soil::WheelSinkageExact(*config.For(c), r, b, w);
        vb::soil::SoilConfig full = config;
        full.grid_spacing_m = spacing;
        spec.speed_mps = 1.0;
        spec.slip = 0.4;
        const double dp = vb::soil::RunWheelRig(full, spec).drawbar_pull_n;
        std::printf("%-5s %6.3f %9.4f %9.4f %6.1f %9.1f\n", Name(c), spacing, z, z_exact,
                    100.0 * (z / z_exact - 1.0), dp);
      }
    }
    std::printf("\n");

    std::printf("solver cost per step (mud, towed at 20 %% slip, median of 3):\n");
    std::printf("grid_m  wheels  us/step  us/wheel  contact_nodes/step\n");
    for (double spacing : {0.1, 0.05, 0.025}) {
      vb::soil::SoilConfig c = config;
      c.grid_spacing_m = spacing;
      long nodes = 0;
      const double us = CostPerStep_us(c, 4, &nodes);
      std::printf("%6.3f %7d %8.1f %9.1f %19ld\n", spacing, 4, us, us / 4, nodes);
    }
    for (int wheels : {1, 2, 4, 8, 16}) {
      long nodes = 0;
      const double us = CostPerStep_us(config, wheels, &nodes);
      std::printf("%6.3f %7d %8.1f %9.1f %19ld\n", config.grid_spacing_m, wheels, us,
                  us / wheels, nodes);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_bench_soil_bin: %s\n", e.what());
    return 2;
  }
  return 0;
}
