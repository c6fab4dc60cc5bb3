#include "vb/soil/wheel_rig.h"

#include <algorithm>
#include <cmath>

#include "vb/soil/scm_soil.h"
#include "vb/terrain/terrain.h"

namespace vb::soil {

namespace {

// A flat 16 m x 16 m bin of one soil class (1 m height grid, 16 x 16 patches).
terrain::TaskSpec FlatBin(terrain::SurfaceClass soil) {
  terrain::TaskSpec t;
  t.name = "soil_bin";
  t.source_file = "<soil bin>";
  t.size_x_m = t.size_y_m = 16.0;
  t.heights.rows = t.heights.cols = 17;
  t.heights.heights_m.assign(17 * 17, 0.0);
  t.max_height_m = 1.0;
  t.patches.rows = t.patches.cols = 16;
  t.patches.classes.assign(256, soil);
  t.patches.friction.assign(256, 0.0);
  return t;
}

}  // namespace

WheelRigResult RunWheelRig(const SoilConfig& config, const WheelRigSpec& spec) {
  const terrain::TaskSpec task = FlatBin(spec.soil);
  const terrain::Terrain ground(task);
  ScmSoil soil(ground, config);

  const double dt = spec.step_s;
  const double mass = spec.load_n / kGravity;  // the load is the weight of the rig's mass
  const double r = spec.radius_m;
  const double x0 = -spec.travel_m / 2.0 - 1.0;
  double z = r + 0.002, vz = 0.0, x = x0;

  WheelSoilInput in;
  in.wheel_id = 0;
  // heading h = (cos a, sin a, 0) (turned left from the towing direction +x), axis z x h
  const double ca = std::cos(spec.slip_angle_rad), sa = std::sin(spec.slip_angle_rad);
  in.axis_W = Vec3(-sa, ca, 0.0);
  in.radius_m = r;
  in.width_m = spec.width_m;
  in.mass_kg = mass;
  WheelRigResult res;

  const long settle_steps = std::lround(spec.settle_s / dt);
  const double travel_time = spec.speed_mps > 0.0 ? spec.travel_m / spec.speed_mps : 0.0;
  const long travel_steps = std::lround(travel_time / dt);
  const long average_from =
      settle_steps + std::lround((spec.travel_m - spec.average_last_m) / std::max(1e-9, spec.speed_mps) / dt);
  const double ramp_steps = std::max(1.0, std::floor(0.7 * static_cast<double>(settle_steps)));
  long n_avg = 0;
  for (long k = 0; k < settle_steps + travel_steps; ++k) {
    const bool towing = k >= settle_steps;
    const double v = towing ? spec.speed_mps : 0.0;
    const double omega = towing ? v * ca / (r * (1.0 - spec.slip)) : 0.0;
    in.center_W = Vec3(x, 0.0, z);
    in.velocity_W = Vec3(v, 0.0, vz);
    in.angular_velocity_W = omega * in.axis_W;
    const WheelSoilOutput out = soil.WheelContact(in, dt);
    soil.EndStep(dt);
    // Semi-implicit Euler of the free vertical motion (as the physics engine integrates). The
    // load is ramped up over the first part of the settling so the plastic sinkage is the
    // static one, not the overshoot of a dropped wheel.
    const double ramp = std::min(1.0, static_cast<double>(k + 1) / ramp_steps);
    vz += dt * (out.force_W.z() - ramp * spec.load_n) / mass;
    z += dt * vz;
    x += dt * v;
    if (k == settle_steps - 1) res.static_sinkage_m = out.sinkage_m;
    if (towing && k >= average_from) {
      ++n_avg;
      res.sinkage_m += out.sinkage_m;
      res.drawbar_pull_n += out.force_W.x();
      res.lateral_force_n += out.force_W.dot(in.axis_W);
      res.drive_torque_nm += -out.torque_W.dot(in.axis_W);
      res.normal_force_n += out.force_W.z();
      res.max_vertical_speed_mps = std::max(res.max_vertical_speed_mps, std::abs(vz));
    }
  }
  if (n_avg > 0) {
    res.sinkage_m /= n_avg;
    res.drawbar_pull_n /= n_avg;
    res.lateral_force_n /= n_avg;
    res.drive_torque_nm /= n_avg;
    res.normal_force_n /= n_avg;
  }
  // Rut and berm halfway along the towed path (well behind the wheel, after it has settled).
  if (travel_steps > 0) {
    const double xm = x0 + 0.6 * spec.travel_m;
    res.rut_depth_m = -soil.SurfaceHeight(xm, 0.0);
    for (double y = spec.width_m / 2.0; y <= spec.width_m / 2.0 + 0.6; y += soil.spacing_m()) {
      res.berm_height_m = std::max({res.berm_height_m, soil.SurfaceHeight(xm, y), soil.SurfaceHeight(xm, -y)});
    }
  }
  res.volume_change_m3 = soil.VolumeChange_m3();
  res.compacted_m3 = soil.CompactedVolume_m3();
  return res;
}

SoilConfig PressureOnly(const SoilConfig& config) {
  SoilConfig c = config;
  c.bulldozing.enabled = false;
  for (auto& s : c.classes) {
    if (!s) continue;
    s->friction_angle_rad = 0.0;
    s->cohesion_pa = 0.0;
  }
  return c;
}

}  // namespace vb::soil
