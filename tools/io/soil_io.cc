#include "io/soil_io.h"

#include <algorithm>

#include <cmath>
#include <string>

#include "io/data_dir.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"
#include "vb/engine/types.h"

namespace vb::io {
namespace {

constexpr const char* kFormatName = "vb-soil";
constexpr int kFormatVersion = 1;
constexpr double kDegToRad = kPi / 180.0;

double AngleDeg(const StrictNode& node, double lo, double hi) {
  const double deg = node.AsDouble();
  if (!(deg > lo && deg < hi)) {
    node.Fail("must be in (" + FormatDouble(lo) + ", " + FormatDouble(hi) + ") degrees, got " +
              FormatDouble(deg));
  }
  return deg * kDegToRad;
}

soil::SoilParams ReadSoil(const StrictNode& node) {
  const StrictMap m = node.AsMap({"bekker_kphi", "bekker_kc", "bekker_n", "cohesion_pa",
                                  "friction_angle_deg", "janosi_shear_m",
                                  "elastic_stiffness_papm", "damping_paspm"});
  soil::SoilParams s;
  s.bekker_kphi = m.Required("bekker_kphi").AsPositive();
  s.bekker_kc = m.Required("bekker_kc").AsNonNegative();
  const StrictNode n = m.Required("bekker_n");
  s.bekker_n = n.AsPositive();
  if (s.bekker_n > 3.0) n.Fail("sinkage exponent above 3 is not a soil (got " + FormatDouble(s.bekker_n) + ")");
  s.cohesion_pa = m.Required("cohesion_pa").AsNonNegative();
  s.friction_angle_rad = AngleDeg(m.Required("friction_angle_deg"), 0.0, 90.0);
  s.janosi_shear_m = m.Required("janosi_shear_m").AsPositive();
  s.elastic_stiffness_papm = m.Required("elastic_stiffness_papm").AsPositive();
  s.damping_paspm = m.Required("damping_paspm").AsNonNegative();
  return s;
}

}  // namespace

soil::SoilConfig LoadSoil(const std::string& path) {
  const StrictNode root = LoadYamlFile(path);
  const StrictMap top =
      root.AsMap({"format", "version", "grid", "bulldozing", "stabilisation", "classes"});
  const StrictNode format = top.Required("format");
  if (format.AsString() != kFormatName) {
    format.Fail("expected format '" + std::string(kFormatName) + "', got '" + format.AsString() +
                "'");
  }
  const StrictNode version = top.Required("version");
  if (version.AsInt() != kFormatVersion) {
    version.Fail("unsupported soil format version " + std::to_string(version.AsInt()) +
                 " (this build reads version " + std::to_string(kFormatVersion) + ")");
  }
  soil::SoilConfig c;
  c.source = path;

  const StrictMap grid = top.Required("grid").AsMap({"spacing_m", "belt_node_stride"});
  const StrictNode spacing = grid.Required("spacing_m");
  c.grid_spacing_m = spacing.AsPositive();
  if (c.grid_spacing_m < 0.005 || c.grid_spacing_m > 0.5) {
    spacing.Fail("must be in [0.005, 0.5] m, got " + FormatDouble(c.grid_spacing_m));
  }
  if (grid.Has("belt_node_stride")) {
    const StrictNode stride = grid.Required("belt_node_stride");
    if (stride.AsInt() != 1 && stride.AsInt() != 2) stride.Fail("must be 1 or 2");
    c.belt_node_stride = static_cast<int>(stride.AsInt());
  }

  const StrictMap bd = top.Required("bulldozing").AsMap(
      {"enabled", "erosion_angle_deg", "flow_factor", "erosion_iterations", "erosion_propagations"});
  c.bulldozing.enabled = bd.Required("enabled").AsBool();
  c.bulldozing.erosion_angle_rad = AngleDeg(bd.Required("erosion_angle_deg"), 0.0, 90.0);
  c.bulldozing.flow_factor = bd.Required("flow_factor").AsNonNegative();
  const StrictNode iters = bd.Required("erosion_iterations");
  const StrictNode props = bd.Required("erosion_propagations");
  if (iters.AsInt() < 0 || iters.AsInt() > 100) iters.Fail("must be in [0, 100]");
  if (props.AsInt() < 0 || props.AsInt() > 100) props.Fail("must be in [0, 100]");
  c.bulldozing.erosion_iterations = static_cast<int>(iters.AsInt());
  c.bulldozing.erosion_propagations = static_cast<int>(props.AsInt());

  const StrictMap st = top.Required("stabilisation").AsMap({"wheel_mass_kg", "wheel_spin_inertia_kgm2"});
  c.default_wheel_mass_kg = st.Required("wheel_mass_kg").AsPositive();
  c.default_wheel_spin_inertia_kgm2 = st.Required("wheel_spin_inertia_kgm2").AsPositive();

  const StrictNode classes_node = top.Required("classes");
  const StrictMap classes = classes_node.AsMap({"mud", "sand", "snow"});
  bool any = false;
  for (const char* name : {"mud", "sand", "snow"}) {
    if (!classes.Has(name)) continue;
    const auto cls = terrain::SurfaceClassFromName(name);
    c.classes[static_cast<size_t>(soil::SoilSlot(*cls))] = ReadSoil(classes.Required(name));
    any = true;
  }
  if (!any) classes_node.Fail("no soil class given (mud, sand, snow)");
  return c;
}

bool NeedsSoil(const terrain::TaskSpec& task) {
  for (terrain::SurfaceClass c : task.patches.classes) {
    if (terrain::IsDeformable(c)) return true;
  }
  return false;
}

std::optional<soil::SoilConfig> LoadSoilIfNeeded(const terrain::TaskSpec& task,
                                                 const std::string& path) {
  if (NeedsSoil(task)) return LoadSoil(path);
  return std::nullopt;
}

std::vector<std::string> SoilNames(const std::string& data_dir) {
  return YamlNamesIn(data_dir + "/soils");
}

}  // namespace vb::io
