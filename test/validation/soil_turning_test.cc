// The lateral (cornering) side of the SCM wheel contact on the original's soils (sand, mud,
// snow), which the drawbar-pull bin and the straight-line tests do not exercise (docs/soil.md
// "Cornering", docs/validation.md "Soil", turning).
//  - Single wheel at a slip angle (the soil bin rig): side force vs Wong's lateral closed form,
//    and how drive slip takes it away (combined slip).
//  - HMMWV steady low-speed circles, soil vs flat rigid ground. Radius: the steady circle radius of the reference point on soil vs on rigid ground (which
//    itself matches the steering geometry, test/validation/vehicle_turning_test.cc).
//  - Force balance: the horizontal soil force summed over the four wheels, resolved towards the
//    circle's centre, vs the centripetal force m v^2 / R of the whole vehicle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "io/soil_io.h"
#include "support/vehicle_sim.h"
#include "support/worlds.h"
#include "vb/engine/physics_world.h"
#include "vb/soil/bekker.h"
#include "vb/soil/scm_soil.h"
#include "vb/soil/wheel_rig.h"
#include "vb/terrain/terrain.h"
#include "vb/terrain/terrain_physics.h"
#include "vb/vehicles/vehicle.h"

namespace vb::soil {
namespace {

using terrain::SurfaceClass;

const char* Name(SurfaceClass c) {
  switch (c) {
    case SurfaceClass::kSnow: return "snow";
    case SurfaceClass::kMud: return "mud";
    case SurfaceClass::kSand: return "sand";
    default: return "rigid";
  }
}

// Passes every query to the solver and sums this step's soil forces over the wheels.
class ForceRecorder : public SoilContact {
 public:
  explicit ForceRecorder(SoilContact* inner) : inner_(inner) {}
  WheelSoilOutput WheelContact(const WheelSoilInput& wheel, double dt) override {
    const WheelSoilOutput out = inner_->WheelContact(wheel, dt);
    step_force_W += out.force_W;
    const Vec3 fwd = wheel.axis_W.cross(Vec3::UnitZ()).normalized();
    const double rim_speed = std::abs(wheel.angular_velocity_W.dot(wheel.axis_W)) * wheel.radius_m;
    const double ground_speed = std::abs(wheel.velocity_W.dot(fwd));
    if (rim_speed > 0.1) max_slip = std::max(max_slip, 1.0 - ground_speed / rim_speed);
    return out;
  }
  void EndStep(double dt) override { inner_->EndStep(dt); }
  Vec3 step_force_W = Vec3::Zero();
  double max_slip = 0.0;  // largest driving slip 1 - v / (omega r) of any wheel this step

 private:
  SoilContact* inner_;
};

struct Circle {
  double radius_m = 0.0;
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
  double centripetal_n = 0.0;     // m v^2 / R
  double soil_inward_n = 0.0;     // soil force towards the centre, summed over the wheels
  double required_inward_n = 0.0; // m a of the centre of mass towards the centre (any motion)
  double sinkage_m = 0.0;         // mean over the wheels
  double drive_slip = 0.0;        // largest driving slip of the four wheels, time mean
};

// The HMMWV started at rest at (0, -15) facing +x on a flat 96 m world of one surface, driven
// with a fixed steering input and the speed controller; averages over the last `window_s`.
Circle SteadyTurn(SurfaceClass surface, double steering, double speed_mps, double seconds,
                  double window_s) {
  const vehicles::VehicleParams p = test::Hmmwv();
  const terrain::TaskSpec task = test::PlaneTask(96.0, 0.0, 0.0, 0.9, surface);
  const terrain::Terrain ground(task);
  engine::PhysicsWorld world;
  vehicles::Vehicle vehicle(p, ground, test::PoseOnPlane(0, -15, 0, 0, 0, p.wheel.radius_m, 0.01),
                            &world);
  std::unique_ptr<ScmSoil> soil;
  std::unique_ptr<ForceRecorder> recorder;
  if (terrain::IsDeformable(surface)) {
    soil = std::make_unique<ScmSoil>(
        ground, io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml"));
    recorder = std::make_unique<ForceRecorder>(soil.get());
    vehicle.SetSoil(recorder.get());
  }
  const double mass = test::TotalMass(p);
  // Position of the vehicle's centre of mass: chassis COM, unsprung masses at the wheel centres
  // (the steering link's few kg go with the chassis).
  const auto com_position = [&](const vehicles::VehicleState& st) {
    Vec3 x = (p.chassis.mass_kg + p.steering.link_mass_kg) *
             (st.pose_W.position + st.pose_W.rotation * p.chassis.com_B);
    for (size_t k = 0; k < st.wheels.size(); ++k) {
      x += test::UnsprungMass(p, p.axles[k / 2]) * st.wheels[k].center_W;
    }
    return Vec3(x / mass);
  };
  Circle c;
  int n = 0;
  const long steps = std::lround(seconds / test::kStep_s);
  const long first = steps - std::lround(window_s / test::kStep_s);
  Vec3 com_before = com_position(vehicle.state());  // before the previous step
  Vec3 com_now = com_before;                          // before this step
  for (long i = 0; i < steps; ++i) {
    const vehicles::VehicleState& s = vehicle.state();
    vehicle.SetInputs(test::SpeedControl(speed_mps, s.forward_speed_mps, steering));
    if (recorder) {
      recorder->step_force_W.setZero();
      recorder->max_slip = 0.0;
    }
    vehicle.Synchronize(test::kStep_s);
    if (soil) soil->EndStep(test::kStep_s);
    world.Step(test::kStep_s);
    vehicle.UpdateState();
    // The step's force changes the velocity by F dt / m and the position by the new velocity
    // times dt (semi-implicit Euler), so F = m (x_next - 2 x + x_prev) / dt^2 exactly.
    const Vec3 com_after = com_position(s);
    const Vec3 com_acceleration =
        (com_after - 2.0 * com_now + com_before) / (test::kStep_s * test::kStep_s);
    com_before = com_now;
    com_now = com_after;
    if (i >= first) {
      const Vec3 v = s.velocity_W;
      const double speed = v.head<2>().norm();
      const double w = s.angular_velocity_W.z();
      c.speed_mps += speed;
      c.yaw_rate_radps += w;
      c.centripetal_n += mass * speed * std::abs(w);
      if (recorder) {
        // inward: the horizontal normal to the velocity, on the side the vehicle turns to
        const Vec3 inward = Vec3(-v.y(), v.x(), 0.0).normalized() * (w >= 0 ? 1.0 : -1.0);
        c.soil_inward_n += recorder->step_force_W.dot(inward);
        c.required_inward_n += mass * com_acceleration.dot(inward);
        c.drive_slip += recorder->max_slip;
      }
      double sink = 0.0;
      for (const vehicles::WheelState& ws : s.wheels) sink += ws.sinkage_m / s.wheels.size();
      c.sinkage_m += sink;
      ++n;
    }
  }
  c.speed_mps /= n;
  c.yaw_rate_radps /= n;
  c.centripetal_n /= n;
  c.soil_inward_n /= n;
  c.required_inward_n /= n;
  c.sinkage_m /= n;
  c.drive_slip /= n;
  c.radius_m = c.speed_mps / std::abs(c.yaw_rate_radps);
  return c;
}

void Print(const char* label, SurfaceClass surface, double steering, const Circle& c) {
  std::printf("%-14s steering %.2f %-5s v %.2f m/s  R %6.2f m  m v^2/R %5.0f N  m a_in %5.0f N"
              "  soil inward %5.0f N  sinkage %.3f m  max drive slip %.2f\n",
              label, steering, Name(surface), c.speed_mps, c.radius_m, c.centripetal_n,
              c.required_inward_n, c.soil_inward_n, c.sinkage_m, c.drive_slip);
}

// Single wheel (the soil bin: HMMWV wheel, 6.1 kN, towed at 1 m/s, free rolling) at slip angles
// 5 ... 30 deg: side force vs Wong's closed form F_y = (A c + W tan phi)[1 - K/(l tan a)(1 -
// e^(-l tan a / K))]. Sand and mud within 25 % (the drawbar-pull tolerance of soil_bin_test);
// every soil: the force rises with the slip angle and stays below the Mohr-Coulomb limit
// A c + W tan(phi). Snow is not held to the closed form (as for the drawbar pull): it rides
// 0.16 m deep (z/r 0.34), where the rim's own longitudinal shear at zero slip (~4 K) takes most of
// the isotropic friction, so the side force builds more slowly; at 30 deg it still reaches
// > 60 % of W tan(phi).
TEST(SoilTurningValidation, SideForceVsSlipAngleMatchesWong) {
  const SoilConfig config =
      io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  for (SurfaceClass surface : {SurfaceClass::kSand, SurfaceClass::kMud, SurfaceClass::kSnow}) {
    const SoilParams& s = *config.For(surface);
    double previous = 0.0;
    for (double deg : {5.0, 10.0, 20.0, 30.0}) {
      WheelRigSpec spec;
      spec.soil = surface;
      spec.slip_angle_rad = deg * test::kDeg;
      const WheelRigResult r = RunWheelRig(config, spec);
      const double wong =
          LateralForceWong(s, spec.radius_m, spec.width_m, spec.load_n, spec.slip_angle_rad);
      const double limit = spec.load_n * std::tan(s.friction_angle_rad) +
                           s.cohesion_pa * spec.width_m * 2.0 * spec.radius_m;
      std::printf("%-5s slip angle %4.1f deg: side force %5.0f N, Wong %5.0f N (%+.0f %%), "
                  "drag %5.0f N, sinkage %.3f m\n",
                  Name(surface), deg, r.lateral_force_n, wong,
                  100.0 * (r.lateral_force_n / wong - 1.0), -r.drawbar_pull_n, r.sinkage_m);
      EXPECT_GT(r.lateral_force_n, previous) << Name(surface) << " " << deg;
      EXPECT_LT(r.lateral_force_n, limit) << Name(surface) << " " << deg;
      if (surface != SurfaceClass::kSnow) {
        EXPECT_NEAR(r.lateral_force_n, wong, 0.25 * wong) << Name(surface) << " " << deg;
      } else if (deg >= 30.0) {
        EXPECT_GT(r.lateral_force_n, 0.6 * spec.load_n * std::tan(s.friction_angle_rad));
      }
      previous = r.lateral_force_n;
    }
  }
}

// Combined slip: the same wheel at 10 deg slip angle, driven at slip 0, 0.4, 0.8. With one
// isotropic Mohr-Coulomb limit per node and the shear along the slip velocity, a fully sheared
// patch gives a side force of about W tan(phi) sin(beta), beta = atan(v_side / v_slip),
// v_side = v sin(a), v_slip = v cos(a) s / (1 - s) (sand's cohesion adds ~40 N): at s = 0.8 that
// is 4 % of the limit. Asserted: the side force falls with drive slip; at s = 0.8 it is below
// 0.2 x its free-rolling value and within 30 % of the estimate (measured sand -6 %, mud -14 %,
// snow -26 %: the front of the patch is not yet fully sheared). At every drive slip of the sweep
// 0 ... 0.95 the side force keeps its sign (it opposes the side slip: a spinning wheel never pushes
// the vehicle the other way, which would reverse the steering).
TEST(SoilTurningValidation, DriveSlipTakesTheSideForce) {
  const SoilConfig config =
      io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
  const double alpha = 10.0 * test::kDeg;
  for (SurfaceClass surface : {SurfaceClass::kSand, SurfaceClass::kMud, SurfaceClass::kSnow}) {
    const SoilParams& s = *config.For(surface);
    double previous = 1e9, free_rolling = 0.0;
    for (double slip : {0.0, 0.2, 0.4, 0.6, 0.8, 0.95}) {
      WheelRigSpec spec;
      spec.soil = surface;
      spec.slip_angle_rad = alpha;
      spec.slip = slip;
      const WheelRigResult r = RunWheelRig(config, spec);
      const double limit = spec.load_n * std::tan(s.friction_angle_rad);
      const double v_slip = std::cos(alpha) * slip / (1.0 - slip);
      const double estimate = limit * std::sin(std::atan2(std::sin(alpha), v_slip));
      std::printf("%-5s slip angle 10 deg, drive slip %.1f: side force %5.0f N (fully sheared "
                  "estimate %5.0f N), pull %5.0f N\n",
                  Name(surface), slip, r.lateral_force_n, estimate, r.drawbar_pull_n);
      EXPECT_LT(r.lateral_force_n, previous) << Name(surface) << " " << slip;
      EXPECT_GT(r.lateral_force_n, 0.0) << Name(surface) << " " << slip;
      if (slip == 0.0) free_rolling = r.lateral_force_n;
      if (slip == 0.8) {
        EXPECT_LT(r.lateral_force_n, 0.2 * free_rolling) << Name(surface);
        EXPECT_NEAR(r.lateral_force_n, estimate, 0.3 * estimate) << Name(surface);
      }
      previous = r.lateral_force_n;
    }
  }
}

// Sand and mud at 3 m/s (lateral acceleration 0.5 / 1 m/s^2, a_y/g 0.05 / 0.1: far below the
// soils' tan(phi) 0.6): the wheels barely slip sideways, so the circle is the rigid one (itself
// the steering geometry's; Chrono full lock 9.5 m) within 5 % (measured within 2 %). The soil's
// horizontal force towards the centre equals m v^2 / R within 5 %: the soil alone carries the
// vehicle round, no force is lost or cancelled between the wheel contact and the chassis.
TEST(SoilTurningValidation, SandAndMudTurnLikeRigidGround) {
  for (double steering : {0.5, 1.0}) {
    const Circle rigid = SteadyTurn(SurfaceClass::kConcrete, steering, 3.0, 10.0, 2.0);
    Print("rigid", SurfaceClass::kConcrete, steering, rigid);
    for (SurfaceClass surface : {SurfaceClass::kSand, SurfaceClass::kMud}) {
      const Circle c = SteadyTurn(surface, steering, 3.0, 10.0, 2.0);
      Print("3 m/s", surface, steering, c);
      EXPECT_NEAR(c.radius_m, rigid.radius_m, 0.05 * rigid.radius_m) << Name(surface);
      EXPECT_NEAR(c.soil_inward_n, c.centripetal_n, 0.05 * c.centripetal_n) << Name(surface);
      EXPECT_GT(c.speed_mps, 2.8) << Name(surface);
    }
  }
}

// Snow (sinkage ~0.12 m at speed): lower cornering stiffness than sand and mud (the rig's snow
// side force at 5 deg is a third of Wong's), so the circle widens a little with lateral
// acceleration, but the drive needs little slip since the damping acts along the terrain normal
// (issue 11; before, a front-arc drag of ~1 kN per wheel kept the drive slip at 0.3-0.5 and the
// wheels spun at 3 m/s, R > 4 x rigid). Asserted: at 1, 2 and 3 m/s, steering 0.5 and full lock,
// R within 10 % of rigid, growing with speed at full lock; the soil force towards the centre
// within 5 % of the inward force the centre of mass needs (m a, measured), at every speed; and
// at 3 m/s, where the circle is steady (drive slip < 0.1), within 5 % of m v^2 / R. At 2 m/s the
// circle is not steady: the P speed controller's drive-slip bursts (slip ~0.4 every ~1.5 s) make
// the yaw rate swing by +-17 %, so m v w of the reference point is 4-6 % above the force the
// vehicle's centre of mass actually needs (issue 24 measured it: soil 426 N = m a 426 N, m v^2/R
// 453 N). Averages over the last 6 s of 16 s.
TEST(SoilTurningValidation, SnowTurnsNearlyLikeRigidGround) {
  for (double steering : {0.5, 1.0}) {
    const Circle rigid = SteadyTurn(SurfaceClass::kConcrete, steering, 1.0, 12.0, 2.0);
    Print("rigid 1 m/s", SurfaceClass::kConcrete, steering, rigid);
    double previous = 0.0;
    for (double speed : {1.0, 2.0, 3.0}) {
      const Circle c = SteadyTurn(SurfaceClass::kSnow, steering, speed, 16.0, 6.0);
      char label[32];
      std::snprintf(label, sizeof(label), "%.0f m/s", speed);
      Print(label, SurfaceClass::kSnow, steering, c);
      EXPECT_NEAR(c.radius_m, rigid.radius_m, 0.10 * rigid.radius_m) << speed;
      if (steering == 1.0) {
        EXPECT_GT(c.radius_m, previous - 0.01) << speed;
      }
      EXPECT_NEAR(c.soil_inward_n, c.required_inward_n, 0.05 * c.required_inward_n) << speed;
      if (speed == 3.0) {
        EXPECT_LT(c.drive_slip, 0.1);
        EXPECT_NEAR(c.soil_inward_n, c.centripetal_n, 0.05 * c.centripetal_n);
      }
      previous = c.radius_m;
    }
  }
}

}  // namespace
}  // namespace vb::soil
