// Tests for tools/io/vehicle_io.cc: the struct-shaped schema, its validation rules, and the
// vehicle list of a data directory.
#include "io/vehicle_io.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "support/input_error.h"

#include "vb/engine/error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

// Every field of VehicleParams, once. Line numbers matter for the error tests.
constexpr char kTinyVehicle[] = R"(name: tiny
chassis:
  mass_kg: 2000.0
  inertia_kgm2: [500.0, 1500.0, 1800.0]
  com_B: [0.1, 0.0, 0.3]
  envelope:
    - {name: box, hull_m: [[2.0, 1.0, -0.1], [2.0, -1.0, -0.1], [-2.0, 1.0, -0.1], [-2.0, -1.0, -0.1], [2.0, 1.0, 1.1], [2.0, -1.0, 1.1], [-2.0, 1.0, 1.1], [-2.0, -1.0, 1.1]]}
axles:
  - x_m: 1.6
    half_track_m: 0.9
    z_m: 0.0
    steered: true
    driven: true
    brake_torque_nm: 2000.0
    suspension:
      model: strut
      stiffness_npm: 150000.0
      damping_nspm: 12000.0
      preload_n: 5000.0
      bump_travel_m: 0.12
      rebound_travel_m: 0.1
      stop_deflection_m: [0.0, 0.01, 0.05]
      stop_force_n: [0.0, 1000.0, 50000.0]
      carrier_mass_kg: 40.0
      carrier_inertia_kgm2: [0.5, 0.6, 0.5]
  - x_m: -1.6
    half_track_m: 0.9
    z_m: 0.0
    steered: false
    driven: false
    brake_torque_nm: 1500.0
    suspension:
      model: strut
      stiffness_npm: 160000.0
      damping_nspm: 13000.0
      preload_n: 5000.0
      bump_travel_m: 0.12
      rebound_travel_m: 0.1
      stop_deflection_m: [0.0, 0.01, 0.05]
      stop_force_n: [0.0, 1000.0, 50000.0]
      carrier_mass_kg: 40.0
      carrier_inertia_kgm2: [0.5, 0.6, 0.5]
steering:
  model: ackermann
  max_angle_rad: 0.55
wheel:
  radius_m: 0.47
  width_m: 0.32
  mass_kg: 60.0
  inertia_kgm2: [4.0, 7.0, 4.0]
tire:
  model: rigid
  friction: 0.9
  normal_stiffness_npm: 400000.0
  normal_damping_nspm: 3000.0
  bristle_stiffness_npm: 200000.0
  bristle_damping_nspm: 2000.0
engine:
  max_speed_radps: 400.0
  map:
    - {speed_radps: 0.0, full_throttle_nm: 300.0, zero_throttle_nm: 0.0}
    - {speed_radps: 200.0, full_throttle_nm: 500.0, zero_throttle_nm: -20.0}
    - {speed_radps: 400.0, full_throttle_nm: 400.0, zero_throttle_nm: -50.0}
transmission:
  forward_ratios: [0.2, 0.4, 0.7]
  reverse_ratio: 0.15
  upshift_rpm: [2500.0, 2500.0, 4000.0]
  downshift_rpm: [0.0, 1200.0, 1200.0]
  min_time_in_gear_s: 0.5
  upshift_on_ground_speed: true
driveline:
  conical_ratio: 0.2
  lock_axle_differentials: false
  lock_central_differential: true
  lock_torque_limit_nm: 1000.0
  driveshaft_inertia_kgm2: 0.5
  central_box_inertia_kgm2: 0.6
  axle_shaft_inertia_kgm2: 0.5
  axle_box_inertia_kgm2: 0.6
)";

class VehicleIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = (fs::path(::testing::TempDir()) /
            ("vb_vehicle_io_" + std::string(info->name()) + "_" + std::to_string(getpid())))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string WriteText(const std::string& name, const std::string& text) const {
    const std::string path = (fs::path(dir_) / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // kTinyVehicle with line `line` (1-based) replaced by `replace`.
  static std::string EditLine(int line, const std::string& replace) {
    return Rewrite(line, line, replace);
  }
  // kTinyVehicle without lines first..last (1-based, inclusive).
  static std::string DeleteLines(int first, int last) { return Rewrite(first, last, ""); }

  static std::string Rewrite(int first, int last, const std::string& replace) {
    std::istringstream in(kTinyVehicle);
    std::string out, text;
    for (int n = 1; std::getline(in, text); ++n) {
      if (n < first || n > last) {
        out += text + "\n";
      } else if (n == first && !replace.empty()) {
        out += replace + "\n";
      }
    }
    return out;
  }

  void ExpectError(const std::string& text, int line, const std::string& key,
                   const std::string& what) {
    const std::string file = WriteText("vehicle.yaml", text);
    test::ExpectInputError([&] { LoadVehicle(file); }, file, line, key, what);
  }

  std::string dir_;
};

TEST_F(VehicleIoTest, LoadsEveryField) {
  const vehicles::VehicleParams v = LoadVehicle(WriteText("tiny.yaml", kTinyVehicle));
  EXPECT_EQ(v.name, "tiny");
  EXPECT_EQ(v.chassis.mass_kg, 2000.0);
  EXPECT_EQ(v.chassis.inertia_kgm2, Vec3(500.0, 1500.0, 1800.0));
  EXPECT_EQ(v.chassis.com_B, Vec3(0.1, 0.0, 0.3));
  ASSERT_EQ(v.chassis.envelope.size(), 1u);
  EXPECT_EQ(v.chassis.envelope[0].name, "box");
  ASSERT_EQ(v.chassis.envelope[0].points_B.size(), 8u);
  EXPECT_EQ(v.chassis.envelope[0].points_B[7], Vec3(-2.0, -1.0, 1.1));
  ASSERT_EQ(v.axles.size(), 2u);
  EXPECT_EQ(v.axles[0].x_m, 1.6);
  EXPECT_EQ(v.axles[0].half_track_m, 0.9);
  EXPECT_TRUE(v.axles[0].steered);
  EXPECT_FALSE(v.axles[1].steered);
  EXPECT_TRUE(v.axles[0].driven);
  EXPECT_FALSE(v.axles[1].driven);
  EXPECT_EQ(v.axles[1].brake_torque_nm, 1500.0);
  EXPECT_EQ(v.axles[1].suspension.stiffness_npm, 160000.0);
  EXPECT_EQ(v.axles[0].suspension.damping_nspm, 12000.0);
  EXPECT_EQ(v.axles[0].suspension.preload_n, 5000.0);
  EXPECT_EQ(v.axles[0].suspension.bump_travel_m, 0.12);
  EXPECT_EQ(v.axles[0].suspension.rebound_travel_m, 0.1);
  EXPECT_EQ(v.axles[0].suspension.carrier_mass_kg, 40.0);
  EXPECT_EQ(v.axles[0].suspension.carrier_inertia_kgm2, Vec3(0.5, 0.6, 0.5));
  EXPECT_EQ(v.steering.max_angle_rad, 0.55);
  EXPECT_EQ(v.steering.model, vehicles::SteeringModel::kAckermann);
  EXPECT_EQ(v.axles[0].suspension.model, vehicles::SuspensionModel::kStrut);
  EXPECT_EQ(v.axles[0].suspension.stop_force_n, (std::vector<double>{0.0, 1000.0, 50000.0}));
  EXPECT_EQ(v.tire.model, vehicles::TireModel::kRigid);
  EXPECT_EQ(v.transmission.min_time_in_gear_s, 0.5);
  EXPECT_TRUE(v.transmission.upshift_on_ground_speed);
  EXPECT_EQ(v.wheel.radius_m, 0.47);
  EXPECT_EQ(v.wheel.width_m, 0.32);
  EXPECT_EQ(v.wheel.mass_kg, 60.0);
  EXPECT_EQ(v.wheel.inertia_kgm2, Vec3(4.0, 7.0, 4.0));
  EXPECT_EQ(v.tire.friction, 0.9);
  EXPECT_EQ(v.tire.normal_stiffness_npm, 400000.0);
  EXPECT_EQ(v.tire.normal_damping_nspm, 3000.0);
  EXPECT_EQ(v.tire.bristle_stiffness_npm, 200000.0);
  EXPECT_EQ(v.tire.bristle_damping_nspm, 2000.0);
  EXPECT_EQ(v.engine.max_speed_radps, 400.0);
  ASSERT_EQ(v.engine.map.size(), 3u);
  EXPECT_EQ(v.engine.map[1].speed_radps, 200.0);
  EXPECT_EQ(v.engine.map[1].full_throttle_nm, 500.0);
  EXPECT_EQ(v.engine.map[2].zero_throttle_nm, -50.0);
  EXPECT_EQ(v.transmission.forward_ratios, (std::vector<double>{0.2, 0.4, 0.7}));
  EXPECT_EQ(v.transmission.reverse_ratio, 0.15);
  EXPECT_EQ(v.transmission.upshift_rpm, (std::vector<double>{2500.0, 2500.0, 4000.0}));
  EXPECT_EQ(v.transmission.downshift_rpm, (std::vector<double>{0.0, 1200.0, 1200.0}));
  EXPECT_EQ(v.driveline.conical_ratio, 0.2);
  EXPECT_FALSE(v.driveline.lock_axle_differentials);
  EXPECT_TRUE(v.driveline.lock_central_differential);
  EXPECT_EQ(v.driveline.lock_torque_limit_nm, 1000.0);
}

TEST_F(VehicleIoTest, ErrorEnvelopeWithoutVolume) {
  // all points in the plane z = 0
  ExpectError(EditLine(7, "    - {name: flat, hull_m: [[1, 1, 0], [1, -1, 0], [-1, 1, 0], [-1, -1, 0], [0, 0, 0]]}"),
              7, "chassis.envelope[0].hull_m", "no convex body: the points span no volume");
  ExpectError(EditLine(7, "    - {name: few, hull_m: [[1, 1, 0], [1, -1, 0], [-1, 1, 1]]}"), 7,
              "chassis.envelope[0].hull_m", "a list of 4 to 256 items");
}

TEST_F(VehicleIoTest, ErrorUnknownKey) {
  ExpectError(EditLine(34, "      stifness_npm: 160000.0"), 34, "axles[1].suspension.stifness_npm",
              "unknown key 'stifness_npm'");
}

TEST_F(VehicleIoTest, ErrorMissingKey) {
  ExpectError(DeleteLines(45, 45), 43, "steering.max_angle_rad",
              "missing required key 'max_angle_rad'");
}

TEST_F(VehicleIoTest, ErrorWrongType) {
  ExpectError(EditLine(12, "    steered: yes"), 12, "axles[0].steered", "expected true or false");
  ExpectError(EditLine(4, "  inertia_kgm2: [500.0, 1500.0]"), 4, "chassis.inertia_kgm2",
              "exactly 3 items");
  ExpectError(EditLine(1, "name: [tiny]"), 1, "name", "expected a string");
}

TEST_F(VehicleIoTest, ErrorOutOfRange) {
  ExpectError(EditLine(3, "  mass_kg: -2000.0"), 3, "chassis.mass_kg", "must be > 0");
  ExpectError(EditLine(18, "      damping_nspm: -1.0"), 18, "axles[0].suspension.damping_nspm",
              "must be >= 0");
  ExpectError(EditLine(47, "  radius_m: 0.0"), 47, "wheel.radius_m", "must be > 0");
  ExpectError(EditLine(45, "  max_angle_rad: 1.6"), 45, "steering.max_angle_rad", "below pi/2");
  ExpectError(EditLine(65, "  forward_ratios: [0.2, 0.0, 0.7]"), 65,
              "transmission.forward_ratios[1]", "must be > 0");
}

TEST_F(VehicleIoTest, ErrorEngineMap) {
  const std::string slower = "    - {speed_radps: 150.0, full_throttle_nm: 1, zero_throttle_nm: 0}";
  ExpectError(EditLine(63, slower), 63, "engine.map[2].speed_radps", "strictly ascending");
  ExpectError(DeleteLines(62, 63), 60, "engine.map", "at least 2 items");
}

TEST_F(VehicleIoTest, ErrorShiftListLength) {
  ExpectError(EditLine(67, "  upshift_rpm: [2500.0, 2500.0]"), 67, "transmission.upshift_rpm",
              "exactly 3 items");
}

TEST_F(VehicleIoTest, ErrorAxles) {
  ExpectError(DeleteLines(26, 42), 8, "axles", "at least 2 items");
  ExpectError(EditLine(26, "  - x_m: 1.7"), 26, "axles[1]", "front to rear");
  ExpectError(EditLine(13, "    driven: false"), 8, "axles", "at least one axle must be driven");
}

TEST_F(VehicleIoTest, ErrorModels) {
  ExpectError(EditLine(16, "      model: coil"), 16, "axles[0].suspension.model",
              "unknown model 'coil'; valid: strut, double_wishbone");
  // a key of the other model is unknown for this one
  ExpectError(EditLine(19, "      spring_free_length_m: 0.3"), 19,
              "axles[0].suspension.spring_free_length_m", "unknown key 'spring_free_length_m'");
  ExpectError(EditLine(23, "      stop_force_n: [0.0, 1000.0]"), 23,
              "axles[0].suspension.stop_force_n", "as many items");
  ExpectError(EditLine(44, "  model: rack_pinion"), 45, "steering.max_angle_rad",
              "unknown key 'max_angle_rad'");
}

TEST_F(VehicleIoTest, ErrorYamlSyntax) {
  ExpectError(EditLine(5, "  com_B: [0.1, 0.0, 0.3]]"), 5, "", "YAML syntax error");
}

TEST_F(VehicleIoTest, VehicleNames) {
  EXPECT_TRUE(VehicleNames((fs::path(dir_) / "nothing").string()).empty());
  fs::create_directories(fs::path(dir_) / "vehicles");
  WriteText("vehicles/zeta.yaml", kTinyVehicle);
  WriteText("vehicles/hmmwv.yaml", kTinyVehicle);
  WriteText("vehicles/notes.txt", "not a vehicle");
  EXPECT_EQ(VehicleNames(dir_), (std::vector<std::string>{"hmmwv", "zeta"}));
}

// Optional driveline key: the engine block reacts the driveshaft torque unless the file says
// false (the original's Chrono powertrain, docs/task_format.md).
TEST_F(VehicleIoTest, EngineBlockReactionIsOptional) {
  EXPECT_TRUE(LoadVehicle(WriteText("a.yaml", kTinyVehicle)).driveline.engine_block_reaction);
  const std::string text = std::string(kTinyVehicle) + "  engine_block_reaction: false\n";
  EXPECT_FALSE(LoadVehicle(WriteText("b.yaml", text)).driveline.engine_block_reaction);
  ExpectError(std::string(kTinyVehicle) + "  engine_block_reaction: 0.5\n", 80,
              "driveline.engine_block_reaction", "expected true or false");
}

// Optional wheel key: the width the soil contact uses, the tire's width unless the file gives
// it (data/vehicles/hmmwv_chrono.yaml: the original's envelope-widened SCM footprint).
TEST_F(VehicleIoTest, SoilFootprintWidthIsOptional) {
  EXPECT_EQ(LoadVehicle(WriteText("a.yaml", kTinyVehicle)).wheel.soil_footprint_width_m, 0.32);
  std::string text = kTinyVehicle;
  const std::string width = "  width_m: 0.32\n";
  const size_t at = text.find(width);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + width.size(), "  soil_footprint_width_m: 0.38\n");
  const vehicles::VehicleParams v = LoadVehicle(WriteText("b.yaml", text));
  EXPECT_EQ(v.wheel.width_m, 0.32);
  EXPECT_EQ(v.wheel.soil_footprint_width_m, 0.38);
  text.replace(text.find("soil_footprint_width_m: 0.38"), 28, "soil_footprint_width_m: -0.1");
  ExpectError(text, 49, "wheel.soil_footprint_width_m", "must be > 0");
}

TEST_F(VehicleIoTest, LoadsShippedHmmwv) {
  const std::string path = VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present yet";
  const vehicles::VehicleParams v = LoadVehicle(path);
  EXPECT_EQ(v.name, "hmmwv");
  EXPECT_GE(v.axles.size(), 2u);
  const std::vector<std::string> names = VehicleNames(VB_SOURCE_DIR "/data");
  EXPECT_NE(std::find(names.begin(), names.end(), "hmmwv"), names.end());
}

// DEF-8 of the probe: a pinion angle below pi/2 whose rack travel the HMMWV's linkage cannot
// follow is bad input at its key, not an internal error when the vehicle is built.
TEST_F(VehicleIoTest, ErrorSteeringTravelTheLinkageCannotFollow) {
  std::ifstream in(VB_SOURCE_DIR "/data/vehicles/hmmwv.yaml", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string from = "max_pinion_angle_rad: 0.5235988";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "max_pinion_angle_rad: 1.5707");
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
  const std::string file = WriteText("wide.yaml", text);
  test::ExpectInputError([&] { LoadVehicle(file); }, file, line, "steering.max_pinion_angle_rad",
                         "the steering linkage does not assemble");
}

// The vehicle library's mechanisms must fit together; a shipped file with one key changed is bad
// input at that key's line. `from` is replaced (its `nth` occurrence, 0-based); the error is
// expected at the line where `at` occurs after the change (the same text if empty).
class VehicleFitTest : public VehicleIoTest {
 protected:
  void ExpectFitError(const std::string& vehicle, const std::string& from, const std::string& to,
                      int nth, const std::string& at, const std::string& key,
                      const std::string& what) {
    std::ifstream in(VB_SOURCE_DIR "/data/vehicles/" + vehicle + ".yaml", std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    size_t pos = text.find(from);
    for (int i = 0; i < nth && pos != std::string::npos; ++i) pos = text.find(from, pos + 1);
    ASSERT_NE(pos, std::string::npos) << from;
    text.replace(pos, from.size(), to);
    const size_t where = at.empty() ? pos : text.find(at, pos);
    ASSERT_NE(where, std::string::npos) << at;
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + where, '\n'));
    const std::string file = WriteText(vehicle + "_bad.yaml", text);
    test::ExpectInputError([&] { LoadVehicle(file); }, file, line, key, what);
  }
};

TEST_F(VehicleFitTest, LibraryLoads) {
  for (const char* name :
       {"art", "vw", "gator", "feda", "man5t", "man7t", "man10t", "m113", "hmmwv_chrono"}) {
    const vehicles::VehicleParams v =
        LoadVehicle(std::string(VB_SOURCE_DIR "/data/vehicles/") + name + ".yaml");
    EXPECT_EQ(v.name, name);
  }
}

// The tracked M113: `tracks` instead of axles, steering, wheel and tire; the loader describes
// the road-wheel stations as axles (vehicle_params.h TrackParams).
TEST_F(VehicleFitTest, TrackedVehicleLoadsWithItsStations) {
  const vehicles::VehicleParams v = LoadVehicle(VB_SOURCE_DIR "/data/vehicles/m113.yaml");
  EXPECT_TRUE(v.tracked);
  ASSERT_EQ(v.axles.size(), 5u);
  EXPECT_DOUBLE_EQ(v.axles[0].x_m, v.tracks.road_wheel_x_m[0]);
  EXPECT_DOUBLE_EQ(v.axles[0].half_track_m, v.tracks.half_gauge_m);
  EXPECT_DOUBLE_EQ(v.wheel.radius_m, v.tracks.road_wheel_radius_m + v.tracks.shoe_height_m);
  EXPECT_EQ(v.transmission.forward_ratios.size(), 4u);
  // wheeled keys are unknown in a tracked file, and the geometry must fit
  ExpectFitError("m113", "engine:", "tire: {}\nengine:", 0, "tire", "tire", "unknown key 'tire'");
  ExpectFitError("m113", "road_wheel_x_m: [1.3335, 0.6665", "road_wheel_x_m: [0.6665, 1.3335", 0,
                 "", "tracks.road_wheel_x_m[1]", "road wheels must be listed front to rear");
  ExpectFitError("m113", "idler_B: [-1.9615", "idler_B: [1.8", 0, "", "tracks.idler_B",
                 "the idler must be at least 0.5 m from the sprocket");
  // the right side's stations (Chrono: 0.085 m behind the left's) must fit too
  EXPECT_DOUBLE_EQ(v.tracks.right_road_wheel_offset_x_m, -0.085);
  ExpectFitError("m113", "right_road_wheel_offset_x_m: -0.085", "right_road_wheel_offset_x_m: -0.7",
                 0, "", "tracks.right_road_wheel_offset_x_m",
                 "the right side's road wheels must lie between the sprocket and the idler");
}

TEST_F(VehicleFitTest, SteeringMustFitTheSteeredAxles) {
  ExpectFitError("man5t", "model: rotary_arm", "model: pitman_arm", 0, "", "steering.model",
                 "pitman_arm steering drives independent suspensions; axle 0 is a solid axle");
  ExpectFitError("art", "model: pitman_arm", "model: rotary_arm", 0, "", "steering.model",
                 "rotary_arm steering drives solid axles through a bellcrank; axle 0 is an "
                 "independent suspension");
  ExpectFitError("man10t", "bellcrank: true", "bellcrank: false", 1, "model: rotary_arm",
                 "steering.model", "axle 1 has no bellcrank");
  ExpectFitError("feda", "      steering_arm_m: 0.1919\n", "", 0, "model: rack_pinion",
                 "steering.model", "rack_pinion steering needs double_wishbone suspension");
  ExpectFitError("gator", "steered: false", "steered: true", 0, "model: rack_pinion",
                 "steering.model", "axle 1 is steered but has a rigid suspension");
}

TEST_F(VehicleFitTest, SuspensionKeysMustFitTheModel) {
  ExpectFitError("man5t", "      bellcrank: true\n",
                 "      bellcrank: true\n      anti_roll_bar_npm: 1000.0\n", 0,
                 "anti_roll_bar_npm", "axles[0].suspension.anti_roll_bar_npm",
                 "an anti-roll bar fits an independent suspension");
  ExpectFitError("vw", "bellcrank: false", "bellcrank: true", 0, "",
                 "axles[1].suspension.bellcrank", "this axle is not steered");
  ExpectFitError("feda", "      model: air_wishbone\n",
                 "      model: air_wishbone\n      bellcrank: true\n", 0, "bellcrank",
                 "axles[0].suspension.bellcrank",
                 "a bellcrank is the steering relay of a solid_axle");
  ExpectFitError("gator", "model: single_wishbone", "model: solid_axle", 0, "steering_arm_m",
                 "axles[0].suspension.steering_arm_m", "not of model 'solid_axle'");
  ExpectFitError("art", "model: dc_motor", "model: turbine", 0, "", "engine.model",
                 "unknown model 'turbine'; valid: map, dc_motor, simple");
  ExpectFitError("vw", "max_step_s: 0.0025", "max_step_s: 0.00001", 0, "", "max_step_s",
                 "must be at least 1e-4 s");
  ExpectFitError("vw", "max_soil_grid_m: 0.0125", "max_soil_grid_m: 0.0002", 0, "",
                 "max_soil_grid_m", "must be at least 0.001 m");
}

// Keys read from the loader's tables (one entry a key) keep their checks and name the file, the
// line and the whole key path, in every mechanism: tracks, TMeasy tire, hard points, solid axle,
// driveline.
TEST_F(VehicleFitTest, TableReadKeysNameFileLineAndKey) {
  ExpectFitError("m113", "torsion_damping_nmsprad: 500.0", "torsion_damping_nmsprad: -1.0", 0,
                 "", "tracks.torsion_damping_nmsprad", "must be >= 0, got -1.0");
  ExpectFitError("m113", "road_wheel_z_m: 0.0", "road_wheel_z_m: [0.1]", 0, "",
                 "tracks.road_wheel_z_m", "expected a number");
  ExpectFitError("hmmwv_tmeasy", "slip_damping_nspm: 2000.0", "slip_damping_nspm: -5.0", 0, "",
                 "tire.slip_damping_nspm", "must be >= 0");
  ExpectFitError("hmmwv", "hardpoints_in:\n        spindle: [-1.59, 35.815, -1.035]\n",
                 "hardpoints_in:\n", 0, "hardpoints_in:",
                 "axles[0].suspension.hardpoints_in.spindle", "missing required key 'spindle'");
  ExpectFitError("man10t", "degression_compression_spm: 3.0", "degression_compression_spm: -3.0",
                 0, "", "axles[0].suspension.degression_compression_spm", "must be >= 0");
  ExpectFitError("feda", "lock_axle_differentials: true", "lock_axle_differentials: 1", 0, "",
                 "driveline.lock_axle_differentials", "expected true or false");
}

}  // namespace
}  // namespace vb::io
