#include "io/vehicle_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/data_dir.h"
#include "io/yaml_strict.h"
#include "vb/engine/convex_shape.h"
#include "vb/engine/error.h"
#include "vb/vehicles/engine_models.h"
#include "vb/vehicles/suspension_forces.h"
#include "vb/vehicles/suspension_kinematics.h"
#include "vb/vehicles/track_running_gear.h"
#include "vb/vehicles/vehicle.h"

namespace vb::io {
namespace {

using vehicles::AxleParams;
using vehicles::VehicleParams;

// The YAML schema is the struct: keys are exactly the field names of vehicle_params.h, with the
// same nesting, and every field is required so a file always states the whole vehicle.

// One required key read into a field of P, with the check its value must pass (the messages
// come from StrictNode and name the file, the line and the key). Tables of these replace a line
// a key; the keys are read in the table's order, so the first bad key is the one reported.
enum Check { kAnyNumber, kPositive, kNonNegative, kBool, kVec3, kPositiveVec3 };

template <class P>
struct Key {
  const char* name;
  Check check;
  double P::*number = nullptr;
  bool P::*flag = nullptr;
  Vec3 P::*vec = nullptr;

  Key(const char* n, Check c, double P::*f) : name(n), check(c), number(f) {}
  Key(const char* n, bool P::*f) : name(n), check(kBool), flag(f) {}
  Key(const char* n, Check c, Vec3 P::*f) : name(n), check(c), vec(f) {}
};

template <class T>
struct Same {
  using type = T;
};

// P is deduced from `p` alone, so a table is written as a plain braced list.
template <class P>
void ReadKeys(const StrictMap& m, P* p, std::initializer_list<Key<typename Same<P>::type>> keys) {
  for (const Key<P>& k : keys) {
    const StrictNode n = m.Required(k.name);
    switch (k.check) {
      case kAnyNumber: p->*k.number = n.AsDouble(); break;
      case kPositive: p->*k.number = n.AsPositive(); break;
      case kNonNegative: p->*k.number = n.AsNonNegative(); break;
      case kBool: p->*k.flag = n.AsBool(); break;
      case kVec3: p->*k.vec = n.AsVec3(); break;
      case kPositiveVec3: p->*k.vec = n.AsPositiveVec3(); break;
    }
  }
}

// Envelope pieces: a name and the points whose convex hull is the piece. The hull is computed here
// once to reject degenerate pieces (flat, collinear) with the file and line; the vehicle computes
// it again when it is built.
std::vector<vehicles::EnvelopePiece> ReadEnvelope(const StrictNode& node) {
  std::vector<vehicles::EnvelopePiece> pieces;
  for (const StrictNode& item : node.AsList(1, 16)) {
    const StrictMap m = item.AsMap({"name", "hull_m"});
    vehicles::EnvelopePiece piece;
    piece.name = m.Required("name").AsString();
    const StrictNode hull = m.Required("hull_m");
    for (const StrictNode& point : hull.AsList(4, 256)) {
      const Vec3 p = point.AsVec3();
      if (p.cwiseAbs().maxCoeff() > 100.0) point.Fail("points must lie within 100 m of the origin");
      piece.points_B.push_back(p);
    }
    engine::ConvexShape shape;
    std::string error;
    // Whether the points bound a convex body (the sample spacing here is only for this check;
    // the vehicle's own spacings are checked in CheckEnvelopeSampling).
    if (!engine::TryMakeConvexHull(piece.points_B, 1.0, &shape, &error)) {
      hull.Fail("no convex body: " + error);
    }
    pieces.push_back(piece);
  }
  return pieces;
}

vehicles::ChassisParams ReadChassis(const StrictNode& node) {
  const StrictMap m = node.AsMap({"mass_kg", "inertia_kgm2", "com_B", "envelope"});
  using P = vehicles::ChassisParams;
  P p;
  ReadKeys(m, &p, {{"mass_kg", kPositive, &P::mass_kg},
                   {"inertia_kgm2", kPositiveVec3, &P::inertia_kgm2},
                   {"com_B", kVec3, &P::com_B}});
  p.envelope = ReadEnvelope(m.Required("envelope"));
  return p;
}

// A sub-schema chosen by its `model` key: the map is opened with all keys any model allows to
// read the model, then re-opened with exactly that model's keys so a key of another model is an
// "unknown key" error at its line.
std::string ReadModel(const StrictNode& node, std::initializer_list<const char*> all_keys,
                      const std::vector<std::string>& models) {
  const StrictNode model = node.AsMap(all_keys).Required("model");
  const std::string name = model.AsString();
  std::string valid;
  for (const std::string& m : models) {
    if (m == name) return name;
    valid += (valid.empty() ? "" : ", ") + m;
  }
  model.Fail("unknown model '" + name + "'; valid: " + valid);
}

// Progressive stop: force vs deflection beyond the stop, ascending, starting at (0, 0).
void ReadStopTable(const StrictMap& m, vehicles::SuspensionParams* p) {
  const StrictNode d = m.Required("stop_deflection_m");
  const StrictNode f = m.Required("stop_force_n");
  for (const StrictNode& item : d.AsList(2)) p->stop_deflection_m.push_back(item.AsNonNegative());
  for (const StrictNode& item : f.AsList(2)) p->stop_force_n.push_back(item.AsNonNegative());
  if (p->stop_force_n.size() != p->stop_deflection_m.size()) {
    f.Fail("must have as many items as stop_deflection_m (" +
           std::to_string(p->stop_deflection_m.size()) + ")");
  }
  if (p->stop_deflection_m[0] != 0.0 || p->stop_force_n[0] != 0.0) {
    d.Fail("the stop table must start at deflection 0 with force 0");
  }
  for (size_t i = 1; i < p->stop_deflection_m.size(); ++i) {
    if (!(p->stop_deflection_m[i] > p->stop_deflection_m[i - 1])) {
      d.Fail("stop deflections must be strictly ascending");
    }
  }
}

vehicles::DoubleWishboneHardpoints ReadHardpoints(const StrictNode& node) {
  const StrictMap m = node.AsMap({"spindle", "uca_f", "uca_b", "uca_u", "lca_f", "lca_b", "lca_u",
                                  "shock_c", "shock_u", "tierod_c", "tierod_u"});
  constexpr double kInchToM = 0.0254;  // hard points are given in inches, as published
  using H = vehicles::DoubleWishboneHardpoints;
  static const std::pair<const char*, Vec3 H::*> kPoints[] = {
      {"spindle", &H::spindle}, {"uca_f", &H::uca_f},     {"uca_b", &H::uca_b},
      {"uca_u", &H::uca_u},     {"lca_f", &H::lca_f},     {"lca_b", &H::lca_b},
      {"lca_u", &H::lca_u},     {"shock_c", &H::shock_c}, {"shock_u", &H::shock_u},
      {"tierod_c", &H::tierod_c}, {"tierod_u", &H::tierod_u}};
  H h;
  for (const auto& [key, point] : kPoints) h.*point = kInchToM * m.Required(key).AsVec3();
  return h;
}

// The carrier (knuckle or axle body): keys every suspension has.
void ReadCarrier(const StrictMap& m, vehicles::SuspensionParams* p) {
  using P = vehicles::SuspensionParams;
  ReadKeys(m, p, {{"carrier_mass_kg", kPositive, &P::carrier_mass_kg},
                  {"carrier_inertia_kgm2", kPositiveVec3, &P::carrier_inertia_kgm2}});
}

// Stops, carrier and (shock models) motion ratio: keys every suspension but `rigid` has.
void ReadStopsAndCarrier(const StrictMap& m, vehicles::SuspensionParams* p) {
  using P = vehicles::SuspensionParams;
  ReadKeys(m, p, {{"bump_travel_m", kNonNegative, &P::bump_travel_m},
                  {"rebound_travel_m", kNonNegative, &P::rebound_travel_m}});
  ReadStopTable(m, p);
  ReadCarrier(m, p);
}

// The shock-based suspensions (single_wishbone, air_wishbone, solid_axle): the shock must stay
// longer than zero over the whole travel the stops allow.
void ReadShock(const StrictMap& m, vehicles::SuspensionParams* p) {
  p->motion_ratio = m.Required("motion_ratio").AsPositive();
  const StrictNode design = m.Required("spring_design_length_m");
  p->spring_design_length_m = design.AsPositive();
  const double hi = p->bump_travel_m + p->stop_deflection_m.back() + 0.03;
  if (!(vehicles::ShockLength(*p, hi) > 0.0)) {
    design.Fail("the shock would be shorter than zero at the end of the bump travel (" +
                FormatDouble(hi) + " m of wheel travel x motion_ratio " +
                FormatDouble(p->motion_ratio) + ")");
  }
}

vehicles::SuspensionParams ReadSuspension(const StrictNode& node, bool steered) {
  vehicles::SuspensionParams p;
  const std::string model = ReadModel(
      node,
      {"model", "stiffness_npm", "preload_n", "spring_stiffness_npm", "spring_free_length_m",
       "hardpoints_in", "damping_nspm", "bump_travel_m", "rebound_travel_m", "stop_deflection_m",
       "stop_force_n", "carrier_mass_kg", "carrier_inertia_kgm2", "spring_design_length_m",
       "motion_ratio", "steering_arm_m", "anti_roll_bar_npm", "spring_preload_n",
       "spring_k2_npm2", "damping_compression_nspm", "degression_compression_spm",
       "damping_expansion_nspm", "degression_expansion_spm", "bellcrank"},
      {"strut", "double_wishbone", "single_wishbone", "wishbone_coilover", "air_wishbone",
       "solid_axle", "rigid"});
  // single_wishbone and wishbone_coilover (a double wishbone without published hard points) are
  // the same reduced model: a coil-over at a constant motion ratio.
  const bool coilover = model == "single_wishbone" || model == "wishbone_coilover";
  const bool independent_shock = coilover || model == "air_wishbone";
  // Mechanism keys that do not fit the model get a message that says why, not just "unknown".
  {
    const StrictMap any = node.AsMap(
        {"model", "stiffness_npm", "preload_n", "spring_stiffness_npm", "spring_free_length_m",
         "hardpoints_in", "damping_nspm", "bump_travel_m", "rebound_travel_m",
         "stop_deflection_m", "stop_force_n", "carrier_mass_kg", "carrier_inertia_kgm2",
         "spring_design_length_m", "motion_ratio", "steering_arm_m", "anti_roll_bar_npm",
         "spring_preload_n", "spring_k2_npm2", "damping_compression_nspm",
         "degression_compression_spm", "damping_expansion_nspm", "degression_expansion_spm",
         "bellcrank"});
    if (any.Has("anti_roll_bar_npm") && !independent_shock) {
      any.Required("anti_roll_bar_npm")
          .Fail("an anti-roll bar fits an independent suspension (single_wishbone, "
                "wishbone_coilover, air_wishbone), not model '" + model + "'");
    }
    if (any.Has("bellcrank") && model != "solid_axle") {
      any.Required("bellcrank").Fail("a bellcrank is the steering relay of a solid_axle, not of "
                                     "model '" + model + "'");
    }
    if (any.Has("steering_arm_m") && !independent_shock) {
      any.Required("steering_arm_m").Fail("steering_arm_m is the knuckle arm of a wishbone "
                                          "without hard points (rack steering), not of model '" +
                                          model + "'");
    }
  }
  if (model == "rigid") {
    const StrictMap m = node.AsMap({"model", "carrier_mass_kg", "carrier_inertia_kgm2"});
    p.model = vehicles::SuspensionModel::kRigid;
    ReadCarrier(m, &p);
    return p;
  }
  if (independent_shock) {
    const bool air = model == "air_wishbone";
    const StrictMap m =
        air ? node.AsMap({"model", "spring_stiffness_npm", "spring_preload_n",
                          "spring_design_length_m", "motion_ratio", "damping_nspm",
                          "steering_arm_m", "anti_roll_bar_npm", "bump_travel_m",
                          "rebound_travel_m",
                          "stop_deflection_m", "stop_force_n", "carrier_mass_kg",
                          "carrier_inertia_kgm2"})
            : node.AsMap({"model", "spring_stiffness_npm", "spring_free_length_m",
                          "spring_design_length_m", "motion_ratio", "damping_nspm",
                          "steering_arm_m", "anti_roll_bar_npm", "bump_travel_m",
                          "rebound_travel_m", "stop_deflection_m", "stop_force_n",
                          "carrier_mass_kg", "carrier_inertia_kgm2"});
    p.model = air ? vehicles::SuspensionModel::kAirWishbone
                  : vehicles::SuspensionModel::kSingleWishbone;
    p.spring_law = air ? vehicles::SpringLaw::kAir : vehicles::SpringLaw::kLinear;
    p.spring_stiffness_npm = m.Required("spring_stiffness_npm").AsPositive();
    if (air) {
      p.spring_preload_n = m.Required("spring_preload_n").AsPositive();
    } else {
      p.spring_free_length_m = m.Required("spring_free_length_m").AsPositive();
    }
    if (m.Has("steering_arm_m")) {
      const StrictNode arm = m.Required("steering_arm_m");
      p.steering_arm_m = arm.AsPositive();
      if (!steered) arm.Fail("steering_arm_m on an axle that is not steered");
    }
    p.damping_nspm = m.Required("damping_nspm").AsNonNegative();
    p.damping_expansion_nspm = p.damping_nspm;
    if (m.Has("anti_roll_bar_npm")) {
      p.anti_roll_bar_npm = m.Required("anti_roll_bar_npm").AsNonNegative();
    }
    ReadStopsAndCarrier(m, &p);
    ReadShock(m, &p);
    return p;
  }
  if (model == "solid_axle") {
    const StrictMap m = node.AsMap(
        {"model", "spring_stiffness_npm", "spring_k2_npm2", "spring_free_length_m",
         "spring_design_length_m", "motion_ratio", "damping_compression_nspm",
         "degression_compression_spm", "damping_expansion_nspm", "degression_expansion_spm",
         "bellcrank", "bump_travel_m", "rebound_travel_m", "stop_deflection_m", "stop_force_n",
         "carrier_mass_kg", "carrier_inertia_kgm2"});
    p.model = vehicles::SuspensionModel::kSolidAxle;
    p.spring_law = vehicles::SpringLaw::kProgressive;
    using P = vehicles::SuspensionParams;
    ReadKeys(m, &p,
             {{"spring_stiffness_npm", kPositive, &P::spring_stiffness_npm},
              {"spring_k2_npm2", kNonNegative, &P::spring_k2_npm2},
              {"spring_free_length_m", kPositive, &P::spring_free_length_m},
              {"damping_compression_nspm", kNonNegative, &P::damping_nspm},
              {"degression_compression_spm", kNonNegative, &P::degression_compression_spm},
              {"damping_expansion_nspm", kNonNegative, &P::damping_expansion_nspm},
              {"degression_expansion_spm", kNonNegative, &P::degression_expansion_spm}});
    const StrictNode bellcrank = m.Required("bellcrank");
    p.bellcrank = bellcrank.AsBool();
    if (p.bellcrank && !steered) {
      bellcrank.Fail("a bellcrank relays the steering: this axle is not steered");
    }
    ReadStopsAndCarrier(m, &p);
    ReadShock(m, &p);
    return p;
  }
  const bool strut = model == "strut";
  const StrictMap m =
      strut ? node.AsMap({"model", "stiffness_npm", "preload_n", "damping_nspm", "bump_travel_m",
                          "rebound_travel_m", "stop_deflection_m", "stop_force_n",
                          "carrier_mass_kg", "carrier_inertia_kgm2"})
            : node.AsMap({"model", "spring_stiffness_npm", "spring_free_length_m",
                          "hardpoints_in", "damping_nspm", "bump_travel_m", "rebound_travel_m",
                          "stop_deflection_m", "stop_force_n", "carrier_mass_kg",
                          "carrier_inertia_kgm2"});
  if (strut) {
    p.model = vehicles::SuspensionModel::kStrut;
    p.stiffness_npm = m.Required("stiffness_npm").AsPositive();
    p.preload_n = m.Required("preload_n").AsNonNegative();
  } else {
    p.model = vehicles::SuspensionModel::kDoubleWishbone;
    p.spring_stiffness_npm = m.Required("spring_stiffness_npm").AsPositive();
    p.spring_free_length_m = m.Required("spring_free_length_m").AsPositive();
    p.hardpoints = ReadHardpoints(m.Required("hardpoints_in"));
  }
  p.damping_nspm = m.Required("damping_nspm").AsNonNegative();
  ReadStopsAndCarrier(m, &p);
  if (!strut) {
    // The linkage must assemble over the whole travel the carrier can reach: the table the
    // vehicle builds, walked the same way (continuation in 1 cm steps). Three solves from
    // scratch (rebound end, 0, bump end) passed hard points that fail in between (NEW-5 of the
    // probe at 8ff4def: an internal error when the vehicle was built).
    try {
      vehicles::CornerShockLengthTable(p);
    } catch (const std::runtime_error&) {
      const vehicles::TravelRange travel = vehicles::CarrierTravel(p);
      char range[64];
      std::snprintf(range, sizeof(range), "%.3f .. %.3f m", travel.lower_m, travel.upper_m);
      m.Required("hardpoints_in").Fail(
          std::string("the linkage does not assemble over the wheel travel ") + range +
          " (rebound and bump travel, the stop stroke and the hard limit beyond it): check the "
          "hard points");
    }
  }
  return p;
}

constexpr double kMaxWheelSize_m = 10.0;   // radius and widths of a wheel

vehicles::WheelParams ReadWheel(const StrictNode& node) {
  const StrictMap m =
      node.AsMap({"radius_m", "width_m", "mass_kg", "inertia_kgm2", "soil_footprint_width_m"});
  using P = vehicles::WheelParams;
  P p;
  ReadKeys(m, &p, {{"radius_m", kPositive, &P::radius_m},
                   {"width_m", kPositive, &P::width_m},
                   {"mass_kg", kPositive, &P::mass_kg},
                   {"inertia_kgm2", kPositiveVec3, &P::inertia_kgm2}});
  p.soil_footprint_width_m = m.Has("soil_footprint_width_m")
                                 ? m.Required("soil_footprint_width_m").AsPositive()
                                 : p.width_m;
  // The soil grid under a wheel and its contact samples are sized by these lengths: a 1000 m
  // wide wheel asked for gigabytes while stepping (B64 of the probe at 8ff4def). 10 m is five
  // times the largest tyre made.
  for (const char* key : {"radius_m", "width_m", "soil_footprint_width_m"}) {
    if (m.Has(key) && m.Required(key).AsDouble() > kMaxWheelSize_m) {
      m.Required(key).Fail("must be at most " + FormatDouble(kMaxWheelSize_m) + " m, got " +
                           FormatDouble(m.Required(key).AsDouble()));
    }
  }
  return p;
}

AxleParams ReadAxle(const StrictNode& node) {
  // `wheel`: an axle whose wheels differ from the vehicle's (the Gator's front and rear tires).
  const StrictMap m = node.AsMap({"x_m", "half_track_m", "z_m", "steered", "driven",
                                  "brake_torque_nm", "suspension", "wheel"});
  using P = AxleParams;
  P p;
  ReadKeys(m, &p, {{"x_m", kAnyNumber, &P::x_m},
                   {"half_track_m", kPositive, &P::half_track_m},
                   {"z_m", kAnyNumber, &P::z_m},
                   {"steered", &P::steered},
                   {"driven", &P::driven},
                   {"brake_torque_nm", kNonNegative, &P::brake_torque_nm}});
  p.suspension = ReadSuspension(m.Required("suspension"), p.steered);
  if (m.Has("wheel")) p.wheel = ReadWheel(m.Required("wheel"));
  return p;
}

std::vector<AxleParams> ReadAxles(const StrictNode& node) {
  std::vector<AxleParams> axles;
  bool any_driven = false;
  for (const StrictNode& item : node.AsList(2)) {
    axles.push_back(ReadAxle(item));
    // Front to rear: the builder and the driveline rely on this order (front axle first).
    if (axles.size() > 1 && !(axles.back().x_m < axles[axles.size() - 2].x_m)) {
      item.Fail("axles must be listed front to rear (x_m strictly decreasing), got x_m " +
                FormatDouble(axles.back().x_m) + " after " +
                FormatDouble(axles[axles.size() - 2].x_m));
    }
    any_driven = any_driven || axles.back().driven;
  }
  if (!any_driven) node.Fail("at least one axle must be driven");
  return axles;
}

vehicles::SteeringParams ReadSteering(const StrictNode& node) {
  vehicles::SteeringParams p;
  const std::string model =
      ReadModel(node,
                {"model", "max_angle_rad", "max_pinion_angle_rad", "pinion_radius_m",
                 "link_mass_kg", "link_position_B", "wheel_per_arm"},
                {"ackermann", "rack_pinion", "pitman_arm", "rotary_arm"});
  // Ackermann geometry and the kinematics break down at a right angle.
  auto below_right_angle = [](const StrictNode& n) {
    const double a = n.AsPositive();
    if (!(a < 0.5 * M_PI)) n.Fail("must be below pi/2, got " + FormatDouble(a));
    return a;
  };
  if (model == "ackermann") {
    const StrictMap m = node.AsMap({"model", "max_angle_rad"});
    p.model = vehicles::SteeringModel::kAckermann;
    p.max_angle_rad = below_right_angle(m.Required("max_angle_rad"));
  } else if (model == "pitman_arm" || model == "rotary_arm") {
    const StrictMap m = node.AsMap({"model", "max_angle_rad", "wheel_per_arm"});
    p.model = model == "pitman_arm" ? vehicles::SteeringModel::kPitmanArm
                                    : vehicles::SteeringModel::kRotaryArm;
    p.max_angle_rad = below_right_angle(m.Required("max_angle_rad"));
    const StrictNode ratio = m.Required("wheel_per_arm");
    p.wheel_per_arm = ratio.AsPositive();
    if (!(p.max_angle_rad * p.wheel_per_arm < 0.5 * M_PI)) {
      ratio.Fail("the road-wheel angle max_angle_rad x wheel_per_arm must be below pi/2, got " +
                 FormatDouble(p.max_angle_rad * p.wheel_per_arm));
    }
  } else {
    const StrictMap m = node.AsMap({"model", "max_pinion_angle_rad", "pinion_radius_m",
                                    "link_mass_kg", "link_position_B"});
    p.model = vehicles::SteeringModel::kRackPinion;
    p.max_pinion_angle_rad = below_right_angle(m.Required("max_pinion_angle_rad"));
    using P = vehicles::SteeringParams;
    ReadKeys(m, &p, {{"pinion_radius_m", kPositive, &P::pinion_radius_m},
                     {"link_mass_kg", kNonNegative, &P::link_mass_kg},
                     {"link_position_B", kVec3, &P::link_position_B}});
  }
  return p;
}


vehicles::TmeasyDirection ReadTmeasyDirection(const StrictNode& node) {
  const StrictMap m = node.AsMap({"df0", "fm", "sm", "fs", "ss"});
  using D = vehicles::TmeasyDirection;
  D d;
  ReadKeys(m, &d, {{"df0", kPositive, &D::df0},
                   {"fm", kPositive, &D::fm},
                   {"sm", kPositive, &D::sm},
                   {"fs", kPositive, &D::fs}});
  const StrictNode ss = m.Required("ss");
  d.ss = ss.AsPositive();
  if (!(d.ss > d.sm)) ss.Fail("sliding slip ss must exceed the peak slip sm");
  return d;
}

vehicles::TireParams ReadTire(const StrictNode& node) {
  using P = vehicles::TireParams;
  P p;
  const std::string model = ReadModel(
      node,
      {"model", "friction", "normal_stiffness_npm", "normal_damping_nspm",
       "bristle_stiffness_npm", "bristle_damping_nspm", "unloaded_radius_m", "width_m",
       "vertical_stiffness_npm", "vertical_damping_nspm", "rim_radius_m", "rim_stiffness_npm",
       "rated_load_n", "longitudinal_at_pn", "longitudinal_at_2pn", "lateral_at_pn",
       "lateral_at_2pn", "mu_0", "rolling_resistance", "relaxation_x_m", "relaxation_y_m",
       "slip_damping_nspm"},
      {"rigid", "tmeasy"});
  if (model == "rigid") {
    const StrictMap m = node.AsMap({"model", "friction", "normal_stiffness_npm",
                                    "normal_damping_nspm", "bristle_stiffness_npm",
                                    "bristle_damping_nspm"});
    p.model = vehicles::TireModel::kRigid;
    ReadKeys(m, &p, {{"friction", kPositive, &P::friction},
                     {"normal_stiffness_npm", kPositive, &P::normal_stiffness_npm},
                     {"normal_damping_nspm", kNonNegative, &P::normal_damping_nspm},
                     {"bristle_stiffness_npm", kPositive, &P::bristle_stiffness_npm},
                     {"bristle_damping_nspm", kNonNegative, &P::bristle_damping_nspm}});
    return p;
  }
  const StrictMap m = node.AsMap(
      {"model", "unloaded_radius_m", "width_m", "vertical_stiffness_npm", "vertical_damping_nspm",
       "rim_radius_m", "rim_stiffness_npm", "rated_load_n", "longitudinal_at_pn", "longitudinal_at_2pn", "lateral_at_pn",
       "lateral_at_2pn", "mu_0", "rolling_resistance", "relaxation_x_m", "relaxation_y_m",
       "slip_damping_nspm"});
  p.model = vehicles::TireModel::kTMeasy;
  ReadKeys(m, &p, {{"unloaded_radius_m", kPositive, &P::unloaded_radius_m},
                   {"width_m", kPositive, &P::width_m},
                   {"vertical_stiffness_npm", kPositive, &P::vertical_stiffness_npm},
                   {"vertical_damping_nspm", kNonNegative, &P::vertical_damping_nspm}});
  const StrictNode rim = m.Required("rim_radius_m");
  p.rim_radius_m = rim.AsPositive();
  if (!(p.rim_radius_m < p.unloaded_radius_m)) rim.Fail("must be below unloaded_radius_m");
  ReadKeys(m, &p, {{"rim_stiffness_npm", kNonNegative, &P::rim_stiffness_npm},
                   {"rated_load_n", kPositive, &P::rated_load_n}});
  p.x_pn = ReadTmeasyDirection(m.Required("longitudinal_at_pn"));
  p.x_2pn = ReadTmeasyDirection(m.Required("longitudinal_at_2pn"));
  p.y_pn = ReadTmeasyDirection(m.Required("lateral_at_pn"));
  p.y_2pn = ReadTmeasyDirection(m.Required("lateral_at_2pn"));
  ReadKeys(m, &p, {{"mu_0", kPositive, &P::mu_0},
                   {"rolling_resistance", kNonNegative, &P::rolling_resistance},
                   {"relaxation_x_m", kPositive, &P::relaxation_x_m},
                   {"relaxation_y_m", kPositive, &P::relaxation_y_m},
                   {"slip_damping_nspm", kNonNegative, &P::slip_damping_nspm}});
  return p;
}

// Engine: a torque map (`model: map`, the default when `model` is absent), a DC motor or
// Chrono's simple engine, both turned into a map (engine_models.h).
vehicles::EngineParams ReadEngine(const StrictNode& node) {
  vehicles::EngineParams p;
  const StrictMap any = node.AsMap({"model", "max_speed_radps", "map", "stall_torque_nm",
                                    "no_load_speed_radps", "rotor_inertia_kgm2", "max_torque_nm",
                                    "max_power_w"});
  const std::string model = any.Has("model")
                                ? ReadModel(node, {"model", "max_speed_radps", "map",
                                                   "stall_torque_nm", "no_load_speed_radps",
                                                   "rotor_inertia_kgm2", "max_torque_nm",
                                                   "max_power_w"},
                                            {"map", "dc_motor", "simple"})
                                : "map";
  if (model == "dc_motor") {
    const StrictMap m = node.AsMap(
        {"model", "stall_torque_nm", "no_load_speed_radps", "rotor_inertia_kgm2"});
    const double no_load = m.Required("no_load_speed_radps").AsPositive();
    p.map = vehicles::DcMotorMap(m.Required("stall_torque_nm").AsPositive(), no_load);
    p.max_speed_radps = vehicles::DcMotorMapEnd(no_load);
    p.rotor_inertia_kgm2 = m.Required("rotor_inertia_kgm2").AsNonNegative();
    return p;
  }
  if (model == "simple") {
    const StrictMap m = node.AsMap({"model", "max_torque_nm", "max_power_w", "max_speed_radps"});
    const double max_speed = m.Required("max_speed_radps").AsPositive();
    p.map = vehicles::SimpleEngineMap(m.Required("max_torque_nm").AsPositive(),
                                      m.Required("max_power_w").AsPositive(), max_speed);
    p.max_speed_radps = vehicles::SimpleEngineMapEnd(max_speed);
    return p;
  }
  const StrictMap m = any.Has("model") ? node.AsMap({"model", "max_speed_radps", "map"})
                                       : node.AsMap({"max_speed_radps", "map"});
  p.max_speed_radps = m.Required("max_speed_radps").AsPositive();
  // Linear interpolation needs two points and strictly ascending speeds.
  for (const StrictNode& item : m.Required("map").AsList(2)) {
    const StrictMap point = item.AsMap({"speed_radps", "full_throttle_nm", "zero_throttle_nm"});
    vehicles::EngineMapPoint q;
    const StrictNode speed = point.Required("speed_radps");
    q.speed_radps = speed.AsNonNegative();
    if (!p.map.empty() && !(q.speed_radps > p.map.back().speed_radps)) {
      speed.Fail("engine map speeds must be strictly ascending, got " +
                 FormatDouble(q.speed_radps) + " after " + FormatDouble(p.map.back().speed_radps));
    }
    q.full_throttle_nm = point.Required("full_throttle_nm").AsDouble();
    q.zero_throttle_nm = point.Required("zero_throttle_nm").AsDouble();
    p.map.push_back(q);
  }
  return p;
}

std::vector<double> ReadPositiveList(const StrictNode& node, size_t min_size) {
  std::vector<double> values;
  for (const StrictNode& item : node.AsList(min_size)) values.push_back(item.AsPositive());
  return values;
}

std::vector<double> ReadShiftList(const StrictNode& node, size_t gears) {
  std::vector<double> values;
  for (const StrictNode& item : node.AsList(gears, gears)) values.push_back(item.AsNonNegative());
  return values;
}

vehicles::TransmissionParams ReadTransmission(const StrictNode& node) {
  const StrictMap m = node.AsMap({"forward_ratios", "reverse_ratio", "upshift_rpm",
                                  "downshift_rpm", "min_time_in_gear_s",
                                  "upshift_on_ground_speed"});
  vehicles::TransmissionParams p;
  p.forward_ratios = ReadPositiveList(m.Required("forward_ratios"), 1);
  // A magnitude: the reverse gear itself flips the direction.
  p.reverse_ratio = m.Required("reverse_ratio").AsPositive();
  p.upshift_rpm = ReadShiftList(m.Required("upshift_rpm"), p.forward_ratios.size());
  p.downshift_rpm = ReadShiftList(m.Required("downshift_rpm"), p.forward_ratios.size());
  using P = vehicles::TransmissionParams;
  ReadKeys(m, &p, {{"min_time_in_gear_s", kNonNegative, &P::min_time_in_gear_s},
                   {"upshift_on_ground_speed", &P::upshift_on_ground_speed}});
  return p;
}

vehicles::DrivelineParams ReadDriveline(const StrictNode& node) {
  const StrictMap m = node.AsMap({"conical_ratio", "lock_axle_differentials",
                                  "lock_central_differential", "lock_torque_limit_nm",
                                  "driveshaft_inertia_kgm2", "central_box_inertia_kgm2",
                                  "axle_shaft_inertia_kgm2", "axle_box_inertia_kgm2",
                                  "lock_coupling_nms_per_rad", "engine_block_reaction"});
  using P = vehicles::DrivelineParams;
  P p;
  if (m.Has("lock_coupling_nms_per_rad")) {
    p.lock_coupling_nms_per_rad = m.Required("lock_coupling_nms_per_rad").AsPositive();
  }
  if (m.Has("engine_block_reaction")) {
    p.engine_block_reaction = m.Required("engine_block_reaction").AsBool();
  }
  ReadKeys(m, &p, {{"conical_ratio", kPositive, &P::conical_ratio},
                   {"lock_axle_differentials", &P::lock_axle_differentials},
                   {"lock_central_differential", &P::lock_central_differential},
                   {"lock_torque_limit_nm", kNonNegative, &P::lock_torque_limit_nm},
                   {"driveshaft_inertia_kgm2", kNonNegative, &P::driveshaft_inertia_kgm2},
                   {"central_box_inertia_kgm2", kNonNegative, &P::central_box_inertia_kgm2},
                   {"axle_shaft_inertia_kgm2", kNonNegative, &P::axle_shaft_inertia_kgm2},
                   {"axle_box_inertia_kgm2", kNonNegative, &P::axle_box_inertia_kgm2}});
  return p;
}

// Steering mechanisms and the suspensions of the steered axles must fit together: a rack needs
// tie-rod hard points (double_wishbone) or a knuckle arm (single_wishbone with steering_arm_m), a
// pitman arm an independent suspension, a rotary arm solid axles with a bellcrank.
void CheckSteeringFits(const VehicleParams& v, const StrictNode& steering) {
  using vehicles::SuspensionModel;
  const StrictNode model = steering.AsMap({"model", "max_angle_rad", "max_pinion_angle_rad",
                                           "pinion_radius_m", "link_mass_kg", "link_position_B",
                                           "wheel_per_arm"})
                               .Required("model");
  const std::string name = model.AsString();
  for (size_t i = 0; i < v.axles.size(); ++i) {
    const vehicles::SuspensionParams& su = v.axles[i].suspension;
    if (!v.axles[i].steered) continue;
    const std::string axle = "axle " + std::to_string(i) + " ";
    const bool independent = su.model != SuspensionModel::kSolidAxle &&
                             su.model != SuspensionModel::kRigid;
    if (su.model == SuspensionModel::kRigid) {
      model.Fail(axle + "is steered but has a rigid suspension (no knuckle to turn)");
    }
    if (name == "rack_pinion" && su.model != SuspensionModel::kDoubleWishbone &&
        !(independent && su.steering_arm_m > 0.0)) {
      model.Fail("rack_pinion steering needs double_wishbone suspension (tie-rod hard points) "
                 "or a wishbone with steering_arm_m on every steered axle; " + axle +
                 "has neither");
    }
    if (name == "pitman_arm" && !independent) {
      model.Fail("pitman_arm steering drives independent suspensions; " + axle +
                 "is a solid axle (use rotary_arm with a bellcrank)");
    }
    if (name == "rotary_arm" && !(su.model == SuspensionModel::kSolidAxle && su.bellcrank)) {
      model.Fail("rotary_arm steering drives solid axles through a bellcrank; " + axle +
                 (independent ? "is an independent suspension" : "has no bellcrank"));
    }
  }
}

// A tracked running gear (vehicle_params.h TrackParams).
vehicles::TrackParams ReadTracks(const StrictNode& node) {
  const StrictMap m = node.AsMap(
      {"half_gauge_m", "shoe_width_m", "shoe_height_m", "belt_mass_kg", "belt_stiffness_npm",
       "sprocket_B", "sprocket_radius_m", "sprocket_mass_kg", "sprocket_inertia_kgm2",
       "brake_torque_nm", "idler_B", "idler_radius_m", "idler_mass_kg", "idler_inertia_kgm2",
       "tensioner_free_length_m", "tensioner_preload_n", "tensioner_stiffness_npm",
       "tensioner_damping_nspm", "tensioner_carrier_mass_kg", "road_wheel_x_m",
       "right_road_wheel_offset_x_m", "road_wheel_z_m",
       "road_wheel_radius_m", "road_wheel_width_m", "road_wheel_mass_kg",
       "road_wheel_inertia_kgm2", "arm_pivot_offset_B", "arm_mass_kg", "arm_inertia_kgm2",
       "torsion_stiffness_nmprad", "torsion_damping_nmsprad", "torsion_preload_nm",
       "bump_angle_rad", "rebound_angle_rad", "stop_stiffness_nmprad", "contact_spacing_m",
       "friction", "normal_stiffness_npm2", "normal_damping_nspm2", "bristle_stiffness_npm2",
       "bristle_damping_nspm2"});
  using T = vehicles::TrackParams;
  T t;
  ReadKeys(m, &t, {{"half_gauge_m", kPositive, &T::half_gauge_m},
                   {"shoe_width_m", kPositive, &T::shoe_width_m},
                   {"shoe_height_m", kNonNegative, &T::shoe_height_m},
                   {"belt_mass_kg", kPositive, &T::belt_mass_kg},
                   {"belt_stiffness_npm", kPositive, &T::belt_stiffness_npm},
                   {"sprocket_B", kVec3, &T::sprocket_B},
                   {"sprocket_radius_m", kPositive, &T::sprocket_radius_m},
                   {"sprocket_mass_kg", kPositive, &T::sprocket_mass_kg},
                   {"sprocket_inertia_kgm2", kPositive, &T::sprocket_inertia_kgm2},
                   {"brake_torque_nm", kNonNegative, &T::brake_torque_nm}});
  const StrictNode idler = m.Required("idler_B");
  t.idler_B = idler.AsVec3();
  if (std::abs(t.idler_B.x() - t.sprocket_B.x()) < 0.5) {
    idler.Fail("the idler must be at least 0.5 m from the sprocket along x");
  }
  ReadKeys(m, &t, {{"idler_radius_m", kPositive, &T::idler_radius_m},
                   {"idler_mass_kg", kPositive, &T::idler_mass_kg},
                   {"idler_inertia_kgm2", kPositive, &T::idler_inertia_kgm2},
                   {"tensioner_free_length_m", kPositive, &T::tensioner_free_length_m},
                   {"tensioner_preload_n", kPositive, &T::tensioner_preload_n},
                   {"tensioner_stiffness_npm", kPositive, &T::tensioner_stiffness_npm},
                   {"tensioner_damping_nspm", kNonNegative, &T::tensioner_damping_nspm},
                   {"tensioner_carrier_mass_kg", kPositive, &T::tensioner_carrier_mass_kg}});
  const StrictNode xs = m.Required("road_wheel_x_m");
  for (const StrictNode& x : xs.AsList(2, vehicles::kMaxRoadWheels)) {
    t.road_wheel_x_m.push_back(x.AsDouble());
    const size_t n = t.road_wheel_x_m.size();
    if (n > 1 && !(t.road_wheel_x_m[n - 1] < t.road_wheel_x_m[n - 2])) {
      x.Fail("road wheels must be listed front to rear (x strictly decreasing)");
    }
  }
  const double front = std::max(t.sprocket_B.x(), t.idler_B.x());
  const double rear = std::min(t.sprocket_B.x(), t.idler_B.x());
  if (!(t.road_wheel_x_m.front() < front && t.road_wheel_x_m.back() > rear)) {
    xs.Fail("the road wheels must lie between the sprocket and the idler");
  }
  if (m.Has("right_road_wheel_offset_x_m")) {
    const StrictNode off = m.Required("right_road_wheel_offset_x_m");
    t.right_road_wheel_offset_x_m = off.AsDouble();
    const double o = t.right_road_wheel_offset_x_m;
    if (!(t.road_wheel_x_m.front() + o < front && t.road_wheel_x_m.back() + o > rear)) {
      off.Fail("the right side's road wheels must lie between the sprocket and the idler");
    }
  }
  ReadKeys(m, &t, {{"road_wheel_z_m", kAnyNumber, &T::road_wheel_z_m},
                   {"road_wheel_radius_m", kPositive, &T::road_wheel_radius_m},
                   {"road_wheel_width_m", kPositive, &T::road_wheel_width_m},
                   {"road_wheel_mass_kg", kPositive, &T::road_wheel_mass_kg},
                   {"road_wheel_inertia_kgm2", kPositive, &T::road_wheel_inertia_kgm2}});
  const StrictNode pivot = m.Required("arm_pivot_offset_B");
  t.arm_pivot_offset_B = pivot.AsVec3();
  if (t.arm_pivot_offset_B.y() != 0.0 ||
      std::hypot(t.arm_pivot_offset_B.x(), t.arm_pivot_offset_B.z()) < 0.05) {
    pivot.Fail("the arm pivot must be at least 0.05 m from the wheel centre in x-z (y = 0)");
  }
  ReadKeys(m, &t, {{"arm_mass_kg", kPositive, &T::arm_mass_kg},
                   {"arm_inertia_kgm2", kPositiveVec3, &T::arm_inertia_kgm2},
                   {"torsion_stiffness_nmprad", kPositive, &T::torsion_stiffness_nmprad},
                   {"torsion_damping_nmsprad", kNonNegative, &T::torsion_damping_nmsprad},
                   {"torsion_preload_nm", kAnyNumber, &T::torsion_preload_nm},
                   {"bump_angle_rad", kPositive, &T::bump_angle_rad},
                   {"rebound_angle_rad", kPositive, &T::rebound_angle_rad},
                   {"stop_stiffness_nmprad", kPositive, &T::stop_stiffness_nmprad}});
  const StrictNode spacing = m.Required("contact_spacing_m");
  t.contact_spacing_m = spacing.AsPositive();
  if (t.contact_spacing_m < 0.01) spacing.Fail("must be at least 0.01 m");
  ReadKeys(m, &t, {{"friction", kPositive, &T::friction},
                   {"normal_stiffness_npm2", kPositive, &T::normal_stiffness_npm2},
                   {"normal_damping_nspm2", kNonNegative, &T::normal_damping_nspm2},
                   {"bristle_stiffness_npm2", kPositive, &T::bristle_stiffness_npm2},
                   {"bristle_damping_nspm2", kNonNegative, &T::bristle_damping_nspm2}});
  return t;
}

// The road-wheel stations of a tracked vehicle as axles (what the runner and the tools count and
// place; vehicle_params.h TrackParams): driven, unsteered, the road wheel with the shoe height
// added to its radius (the belt's bottom).
void TrackStations(VehicleParams* v) {
  const vehicles::TrackParams& t = v->tracks;
  v->wheel.radius_m = t.road_wheel_radius_m + t.shoe_height_m;
  v->wheel.width_m = t.shoe_width_m;
  v->wheel.mass_kg = t.road_wheel_mass_kg;
  v->wheel.inertia_kgm2 = Vec3(1.0, t.road_wheel_inertia_kgm2, 1.0);
  v->tire.friction = t.friction;
  for (double x : t.road_wheel_x_m) {
    AxleParams a;
    a.x_m = x;
    a.half_track_m = t.half_gauge_m;
    a.z_m = t.road_wheel_z_m;
    a.steered = false;
    a.driven = true;
    a.brake_torque_nm = 0.0;
    a.suspension.carrier_mass_kg = t.arm_mass_kg;
    v->axles.push_back(a);
  }
}

// The chassis envelope's sample points for obstacle contact are spaced by the wheel radius
// (vehicles::EnvelopeObstacleSpacing_m): a tiny wheel on a big body would ask for millions of
// them (NEW-4 of the probe at 8ff4def: a 1e-6 m wheel took 8 GB, then std::bad_alloc).
void CheckEnvelopeSampling(const VehicleParams& v, const StrictNode& radius_node) {
  const double spacing_m = vehicles::EnvelopeObstacleSpacing_m(v);
  for (const vehicles::EnvelopePiece& piece : v.chassis.envelope) {
    engine::ConvexShape shape;
    std::string error;
    if (!engine::TryMakeConvexHull(piece.points_B, 1.0, &shape, &error)) continue;   // checked
    const double samples = engine::ShapeSampleCount(shape, spacing_m);
    if (samples > engine::kMaxShapeSamples) {
      radius_node.Fail("the chassis envelope piece '" + piece.name + "' is sampled for obstacle "
                       "contact every 0.1 x radius_m = " + FormatDouble(spacing_m) + " m: " +
                       std::to_string(static_cast<long long>(std::min(samples, 1e18))) +
                       " points, more than the limit of " +
                       std::to_string(static_cast<long long>(engine::kMaxShapeSamples)) +
                       "; a wheel this small needs a smaller envelope");
    }
  }
}

}  // namespace

vehicles::VehicleParams LoadVehicle(const std::string& path) {
  const StrictNode root = LoadYamlFile(path);
  const StrictMap any = root.AsMap({"name", "chassis", "axles", "steering", "wheel", "tire",
                                    "engine", "transmission", "driveline", "max_step_s",
                                    "max_soil_grid_m", "tracks"});
  // A tracked vehicle has `tracks` instead of axles, steering, wheel and tire.
  const bool tracked = any.Has("tracks");
  const StrictMap top =
      tracked ? root.AsMap({"name", "chassis", "tracks", "engine", "transmission", "driveline",
                            "max_step_s", "max_soil_grid_m"})
              : root.AsMap({"name", "chassis", "axles", "steering", "wheel", "tire", "engine",
                            "transmission", "driveline", "max_step_s", "max_soil_grid_m"});
  VehicleParams v;
  const StrictNode name = top.Required("name");
  v.name = name.AsString();
  if (v.name.empty()) name.Fail("name is empty");
  if (top.Has("max_step_s")) {
    const StrictNode step = top.Required("max_step_s");
    v.max_step_s = step.AsPositive();
    if (v.max_step_s < 1e-4) {
      step.Fail("must be at least 1e-4 s, got " + FormatDouble(v.max_step_s));
    }
  }
  if (top.Has("max_soil_grid_m")) {
    const StrictNode grid = top.Required("max_soil_grid_m");
    v.max_soil_grid_m = grid.AsPositive();
    if (v.max_soil_grid_m < 1e-3) {   // a finer grid's tiles would not fit a world in memory
      grid.Fail("must be at least 0.001 m, got " + FormatDouble(v.max_soil_grid_m));
    }
  }
  v.chassis = ReadChassis(top.Required("chassis"));
  if (tracked) {
    v.tracked = true;
    v.tracks = ReadTracks(top.Required("tracks"));
    TrackStations(&v);
    v.engine = ReadEngine(top.Required("engine"));
    v.transmission = ReadTransmission(top.Required("transmission"));
    v.driveline = ReadDriveline(top.Required("driveline"));
    return v;
  }
  v.axles = ReadAxles(top.Required("axles"));
  v.steering = ReadSteering(top.Required("steering"));
  CheckSteeringFits(v, top.Required("steering"));
  if (v.steering.model == vehicles::SteeringModel::kRackPinion) {
    // The rack's whole travel must assemble too (DEF-8 of the probe: a pinion angle just below
    // pi/2 on the HMMWV pulls the tie rod past where the linkage closes). The same table the
    // vehicle builds, so a vehicle that loads always builds.
    const StrictMap steering = top.Required("steering").AsMap(
        {"model", "max_pinion_angle_rad", "pinion_radius_m", "link_mass_kg", "link_position_B"});
    const double rack_max_m = v.steering.max_pinion_angle_rad * v.steering.pinion_radius_m;
    for (const AxleParams& axle : v.axles) {
      if (!axle.steered) continue;
      if (axle.suspension.model != vehicles::SuspensionModel::kDoubleWishbone) break;
      try {
        vehicles::SteerAngleTable(axle.suspension.hardpoints, rack_max_m, vehicles::kSteerAngleTableSamples);
      } catch (const std::runtime_error&) {
        steering.Required("max_pinion_angle_rad")
            .Fail("the steering linkage does not assemble over the rack travel of +-" +
                  FormatDouble(rack_max_m) + " m (max_pinion_angle_rad x pinion_radius_m): "
                  "reduce the angle");
      }
      break;   // all steered axles share the first one's tie-rod geometry (vehicle.cc)
    }
  }
  v.wheel = ReadWheel(top.Required("wheel"));
  CheckEnvelopeSampling(v, top.Required("wheel")
                               .AsMap({"radius_m", "width_m", "mass_kg", "inertia_kgm2",
                                       "soil_footprint_width_m"})
                               .Required("radius_m"));
  v.tire = ReadTire(top.Required("tire"));
  v.engine = ReadEngine(top.Required("engine"));
  v.transmission = ReadTransmission(top.Required("transmission"));
  v.driveline = ReadDriveline(top.Required("driveline"));
  return v;
}

std::vector<std::string> VehicleNames(const std::string& data_dir) {
  // A missing directory simply has no vehicles; callers report "unknown vehicle" with the list.
  return YamlNamesIn(data_dir + "/vehicles");
}

}  // namespace vb::io
