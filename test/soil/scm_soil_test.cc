// ScmSoil unit behaviour: which wheels it claims, sparse memory, elastic unloading, shear reset,
// volume bookkeeping, determinism and configuration errors.
#include "vb/soil/scm_soil.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "io/soil_io.h"
#include "support/worlds.h"
#include "vb/engine/error.h"
#include "vb/terrain/terrain.h"

namespace vb::soil {
namespace {

SoilConfig Config() {
  return io::LoadSoil(std::string(VB_SOURCE_DIR) + "/data/soils/verti_bench.yaml");
}

WheelSoilInput Wheel(double x, double z) {
  WheelSoilInput w;
  w.center_W = Vec3(x, 0.0, z);
  w.axis_W = Vec3::UnitY();
  w.radius_m = 0.467;
  w.width_m = 0.254;
  return w;
}

// Presses a wheel quasi-statically to the centre height z (moving down 1 mm per step).
WheelSoilOutput PressTo(ScmSoil* soil, double x, double z_from, double z_to) {
  WheelSoilOutput out;
  for (double z = z_from; z >= z_to - 1e-12; z -= 0.001) {
    out = soil->WheelContact(Wheel(x, z), 0.005);
    soil->EndStep(0.005);
  }
  return out;
}

TEST(ScmSoilTest, ClaimsOnlyWheelsOverDeformablePatches) {
  terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kMud);
  // Western half rigid (patch columns 0..7: x < 0).
  for (int r = 0; r < 16; ++r) {
    for (int c = 0; c < 8; ++c) {
      task.patches.classes[static_cast<size_t>(r * 16 + c)] = terrain::SurfaceClass::kDirt;
      task.patches.friction[static_cast<size_t>(r * 16 + c)] = 0.6;
    }
  }
  const terrain::Terrain ground(task);
  ScmSoil soil(ground, Config());
  EXPECT_FALSE(soil.WheelContact(Wheel(-10.0, 0.4), 0.005).on_soil);
  const WheelSoilOutput above = soil.WheelContact(Wheel(10.0, 0.6), 0.005);
  EXPECT_TRUE(above.on_soil);
  EXPECT_EQ(above.surface, terrain::SurfaceClass::kMud);
  EXPECT_EQ(above.force_W, Vec3::Zero());
  const WheelSoilOutput in = soil.WheelContact(Wheel(10.0, 0.44), 0.005);
  EXPECT_GT(in.force_W.z(), 0.0);
  EXPECT_NEAR(in.sinkage_m, 0.027, 1e-9);
}

TEST(ScmSoilTest, MemoryIsProportionalToTheTouchedArea) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kSnow);
  const terrain::Terrain ground(task);
  ScmSoil soil(ground, Config());
  EXPECT_EQ(soil.stats().tiles, 0);
  // Roll a pressed wheel 10 m along x.
  for (int k = 0; k < 1000; ++k) {
    WheelSoilInput w = Wheel(-5.0 + 0.01 * k, 0.40);
    w.velocity_W = Vec3(2.0, 0.0, 0.0);
    w.angular_velocity_W = Vec3(0.0, 2.0 / 0.467, 0.0);
    soil.WheelContact(w, 0.005);
    soil.EndStep(0.005);
  }
  // 16 x 16 tiles of 0.05 m = 0.8 m squares; a 10 m track with its rim spans ~2 x 14 tiles,
  // far from the 160 x 160 tiles of the world.
  EXPECT_GT(soil.stats().tiles, 10);
  EXPECT_LT(soil.stats().tiles, 60);
  EXPECT_LT(soil.stats().memory_bytes, 2u << 20);
}

TEST(ScmSoilTest, UnloadingIsElasticAndReloadingDoesNotCompactAgain) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kMud);
  const terrain::Terrain ground(task);
  SoilConfig config = Config();
  config.bulldozing.enabled = false;
  ScmSoil soil(ground, config);
  const WheelSoilOutput loaded = PressTo(&soil, 0.0, 0.47, 0.417);  // 5 cm sinkage
  const double compacted = soil.CompactedVolume_m3();
  EXPECT_GT(loaded.force_W.z(), 3000.0);
  // 5 mm up: the elastic spring lets go completely. (The stability cap at 5 ms and the default
  // 99.5 kg wheel mass lowers Ke from 2e8 to ~3.6e7 Pa/m here: ~2 mm of elastic sinkage.)
  EXPECT_NEAR(soil.WheelContact(Wheel(0.0, 0.422), 0.005).force_W.z(), 0.0, 1e-9);
  soil.EndStep(0.005);
  // Back down to the same depth: the same force, no new plastic sinkage.
  const WheelSoilOutput again = soil.WheelContact(Wheel(0.0, 0.417), 0.005);
  EXPECT_NEAR(again.force_W.z(), loaded.force_W.z(), 0.01 * loaded.force_W.z());
  EXPECT_NEAR(soil.CompactedVolume_m3(), compacted, 1e-12);
  EXPECT_NEAR(soil.VolumeChange_m3(), -compacted, 1e-12);  // without flow, compaction is lost
}

TEST(ScmSoilTest, ShearBuildsWithSlipAndRestartsAfterLosingContact) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kMud);
  const terrain::Terrain ground(task);
  SoilConfig config = Config();
  config.bulldozing.enabled = false;
  ScmSoil soil(ground, config);
  PressTo(&soil, 0.0, 0.47, 0.417);
  // Spin in place: the rim slides over the soil, the soil pushes back along +x more and more.
  WheelSoilInput w = Wheel(0.0, 0.417);
  w.angular_velocity_W = Vec3(0.0, 1.0, 0.0);  // bottom moves towards -x
  double fx_first = 0.0, fx = 0.0;
  for (int k = 0; k < 20; ++k) {
    fx = soil.WheelContact(w, 0.005).force_W.x();
    soil.EndStep(0.005);
    if (k == 0) fx_first = fx;
  }
  EXPECT_GT(fx_first, 0.0);
  EXPECT_GT(fx, 3.0 * fx_first);  // Janosi: 1 - exp(-j/K) grows with j = 20 x 2.3 mm
  // Lift off for one step, put it back: shear displacement restarts from zero.
  soil.WheelContact(Wheel(0.0, 0.6), 0.005);
  soil.EndStep(0.005);
  const double fx_back = soil.WheelContact(w, 0.005).force_W.x();
  EXPECT_NEAR(fx_back, fx_first, 0.05 * fx_first);
}

TEST(ScmSoilTest, BulldozingConservesVolumeAndRaisesARim) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kSnow);
  const terrain::Terrain ground(task);
  ScmSoil soil(ground, Config());
  for (int k = 0; k < 400; ++k) {
    WheelSoilInput w = Wheel(-1.0 + 0.005 * k, 0.30);
    w.velocity_W = Vec3(1.0, 0.0, 0.0);
    w.angular_velocity_W = Vec3(0.0, 1.0 / 0.467, 0.0);
    soil.WheelContact(w, 0.005);
    soil.EndStep(0.005);
  }
  EXPECT_GT(soil.CompactedVolume_m3(), 0.02);
  EXPECT_NEAR(soil.VolumeChange_m3(), 0.0, 1e-12 * soil.CompactedVolume_m3() + 1e-15);
  EXPECT_EQ(soil.stats().lost_volume_m3, 0.0);
  EXPECT_LT(soil.SurfaceHeight(0.0, 0.0), -0.05);                  // rut
  EXPECT_GT(std::max(soil.SurfaceHeight(0.0, 0.2), soil.SurfaceHeight(0.0, 0.25)), 0.02);  // berm
}

TEST(ScmSoilTest, SameInputsGiveTheSameBits) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kSand);
  const terrain::Terrain ground(task);
  ScmSoil a(ground, Config()), b(ground, Config());
  for (int k = 0; k < 200; ++k) {
    WheelSoilInput w = Wheel(0.01 * k, 0.455 - 0.00001 * k);
    w.velocity_W = Vec3(2.0, 0.1, -0.01);
    w.angular_velocity_W = Vec3(0.0, 5.0, 0.2);
    const WheelSoilOutput oa = a.WheelContact(w, 0.005), ob = b.WheelContact(w, 0.005);
    a.EndStep(0.005);
    b.EndStep(0.005);
    ASSERT_EQ(std::memcmp(oa.force_W.data(), ob.force_W.data(), sizeof(double) * 3), 0);
    ASSERT_EQ(std::memcmp(oa.torque_W.data(), ob.torque_W.data(), sizeof(double) * 3), 0);
  }
}

// The rim and erosion passes find a node's 4-neighbours from per-node links and per-tile
// neighbour pointers instead of the grid look-up: on worlds whose edges fall inside a tile and
// on a tile border, with wheels pressed and dragged at random places (the world's edges
// included), headings and cambers, so that tiles are allocated in many orders by the scan, the
// rim and the erosion, every allocated node's neighbours must be the look-up's; also in a soil
// restored from a snapshot (whose tiles are copies).
TEST(ScmSoilTest, NeighbourLinksAreTheGridLookUps) {
  for (const double size : {10.0, 12.0}) {
    const terrain::TaskSpec task =
        test::PlaneTask(size, 0.0, 0.0, 0.0, terrain::SurfaceClass::kSnow);
    const terrain::Terrain ground(task);
    ScmSoil soil(ground, Config());
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> pos(-0.5 * size - 0.3, 0.5 * size + 0.3);
    std::uniform_real_distribution<double> heading(-M_PI, M_PI), camber(-0.3, 0.3);
    for (int wheel = 0; wheel < 60; ++wheel) {
      const double x = pos(rng), y = pos(rng), psi = heading(rng), tilt = camber(rng);
      for (int k = 0; k < 20; ++k) {
        WheelSoilInput w = Wheel(0.0, 0.0);
        w.center_W = Vec3(x + 0.01 * k * std::cos(psi), y + 0.01 * k * std::sin(psi),
                          0.45 - 0.004 * k);
        w.axis_W = Vec3(-std::sin(psi), std::cos(psi), tilt).normalized();
        w.velocity_W = Vec3(2.0 * std::cos(psi), 2.0 * std::sin(psi), 0.0);
        soil.WheelContact(w, 0.005);
        soil.EndStep(0.005);
      }
      ASSERT_TRUE(soil.NeighbourLinksMatchLookUps()) << "size " << size << ", wheel " << wheel;
    }
    EXPECT_GT(soil.stats().tiles, 40);
    ScmSoil restored(ground, Config());
    restored.Restore(soil.Snapshot());
    EXPECT_TRUE(restored.NeighbourLinksMatchLookUps());
    soil.Restore(soil.Snapshot());
    EXPECT_TRUE(soil.NeighbourLinksMatchLookUps());
  }
}

TEST(ScmSoilTest, UndescribedSoilClassIsAnInputError) {
  const terrain::TaskSpec task = test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kSnow);
  const terrain::Terrain ground(task);
  SoilConfig config = Config();
  config.classes[static_cast<size_t>(SoilSlot(terrain::SurfaceClass::kSnow))].reset();
  try {
    ScmSoil soil(ground, config);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "snow");
    EXPECT_NE(std::string(e.what()).find("does not describe"), std::string::npos) << e.what();
  }
}

// A straight belt (2 m x 0.38 m, across the grid's columns off a node line) pressed into sand
// quasi-statically, 1 mm per step to 20 mm: the track contact's coarse grid (belt_node_stride 2:
// every second node each way, carrying four cells) bears what the full grid does, and leaves a
// rut at the grid's resolution: every node under the belt has sunk, the odd ones as the even.
TEST(ScmSoilTest, BeltCoarseGridBearsAsTheFullGridAndLeavesARut) {
  const terrain::TaskSpec task =
      test::PlaneTask(128.0, 0.0, 0.0, 0.0, terrain::SurfaceClass::kSand);
  const terrain::Terrain ground(task);
  constexpr double kY = 0.013, kHw = 0.19;
  double fz[3] = {0.0, 0.0, 0.0};
  for (int stride : {1, 2}) {
    SoilConfig config = Config();
    config.belt_node_stride = stride;
    ScmSoil soil(ground, config);
    TrackSoilInput in;
    in.n_points = 2;
    in.width_m = 2.0 * kHw;
    in.lateral_W = Vec3::UnitY();
    in.mass_kg = 500.0;
    for (Vec3& v : in.velocities_W) v.setZero();   // Eigen leaves them uninitialised
    TrackSoilOutput out;
    for (double z = 0.001; z >= -0.020 - 1e-12; z -= 0.001) {
      in.points_W[0] = Vec3(-1.0, kY, z);
      in.points_W[1] = Vec3(1.0, kY, z);
      out = soil.TrackContact(in, 0.005);
      soil.EndStep(0.005);
    }
    fz[stride] = out.point_force_W[0].z() + out.point_force_W[1].z();
    // the rut: every node well under the belt (not its edges or ends) has sunk below the belt's
    // elastic contact level, within rounding of one another
    const double dx = soil.spacing_m();
    double lo = 1e300, hi = -1e300;
    for (int j = static_cast<int>(std::ceil((kY - kHw + dx) / dx));
         j * dx <= kY + kHw - dx; ++j) {
      for (int i = -15; i <= 15; ++i) {
        const double h = soil.SurfaceHeight(i * dx, j * dx);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
      }
    }
    std::printf("stride %d: vertical force %.0f N, rut levels %.5f .. %.5f m\n", stride,
                fz[stride], lo, hi);
    EXPECT_LT(hi, -0.005) << "stride " << stride;
    EXPECT_NEAR(lo, hi, 1e-3) << "stride " << stride;
    // beside the belt the soil has not sunk (it took the displaced soil)
    EXPECT_GE(soil.SurfaceHeight(0.0, kY + kHw + 2.0 * dx), 0.0);
    EXPECT_GE(soil.SurfaceHeight(0.0, kY - kHw - 2.0 * dx), 0.0);
  }
  EXPECT_GT(fz[1], 1000.0);
  EXPECT_NEAR(fz[2], fz[1], 0.03 * fz[1]);
}

}  // namespace
}  // namespace vb::soil
