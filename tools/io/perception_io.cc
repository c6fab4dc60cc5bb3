#include "io/perception_io.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include "io/data_dir.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"

namespace vb::io {
namespace {

constexpr const char* kFormatName = "vb-perception";
constexpr int kFormatVersion = 1;

// Reads `name` of a section if present, remembering its line for later range errors.
struct SectionReader {
  const StrictMap& map;
  std::string section;
  std::map<std::string, int>* lines;
  void Read(const char* name, double* out) const {
    if (!map.Has(name)) return;
    const StrictNode n = map.Required(name);
    *out = n.AsDouble();
    (*lines)[section + "." + name] = n.line();
  }
};

}  // namespace

runner::PerceptionParams LoadPerception(const std::string& path) {
  const StrictNode root = LoadYamlFile(path);
  const StrictMap top = root.AsMap(
      {"format", "version", "description", "pose", "maps", "semantics", "obstacles", "latency_s"});
  const StrictNode format = top.Required("format");
  if (format.AsString() != kFormatName) {
    format.Fail("expected format '" + std::string(kFormatName) + "', got '" + format.AsString() +
                "'");
  }
  const StrictNode version = top.Required("version");
  if (version.AsInt() != kFormatVersion) {
    version.Fail("unsupported perception format version " + std::to_string(version.AsInt()) +
                 " (this build reads version " + std::to_string(kFormatVersion) + ")");
  }
  if (top.Has("description")) top.Required("description").AsString();

  runner::PerceptionParams p;
  p.name = std::filesystem::path(path).stem().string();
  std::map<std::string, int> lines;
  if (top.Has("pose")) {
    const StrictMap m = top.Required("pose").AsMap(
        {"position_bias_sd_m", "position_drift_m_per_sqrt_s", "position_noise_sd_m",
         "yaw_bias_sd_rad", "yaw_drift_rad_per_sqrt_s", "yaw_noise_sd_rad",
         "attitude_noise_sd_rad", "noise_correlation_s", "velocity_noise_sd_mps",
         "angular_velocity_noise_sd_radps"});
    const SectionReader r{m, "pose", &lines};
    r.Read("position_bias_sd_m", &p.position_bias_sd_m);
    r.Read("position_drift_m_per_sqrt_s", &p.position_drift_m_per_sqrt_s);
    r.Read("position_noise_sd_m", &p.position_noise_sd_m);
    r.Read("yaw_bias_sd_rad", &p.yaw_bias_sd_rad);
    r.Read("yaw_drift_rad_per_sqrt_s", &p.yaw_drift_rad_per_sqrt_s);
    r.Read("yaw_noise_sd_rad", &p.yaw_noise_sd_rad);
    r.Read("attitude_noise_sd_rad", &p.attitude_noise_sd_rad);
    r.Read("noise_correlation_s", &p.noise_correlation_s);
    r.Read("velocity_noise_sd_mps", &p.velocity_noise_sd_mps);
    r.Read("angular_velocity_noise_sd_radps", &p.angular_velocity_noise_sd_radps);
  }
  if (top.Has("maps")) {
    const StrictMap m = top.Required("maps").AsMap(
        {"map_cell_m", "elevation_noise_sd_m", "elevation_hole_fraction", "elevation_hole_size_m",
         "mapping_delay_s"});
    const SectionReader r{m, "maps", &lines};
    r.Read("map_cell_m", &p.map_cell_m);
    r.Read("elevation_noise_sd_m", &p.elevation_noise_sd_m);
    r.Read("elevation_hole_fraction", &p.elevation_hole_fraction);
    r.Read("elevation_hole_size_m", &p.elevation_hole_size_m);
    r.Read("mapping_delay_s", &p.mapping_delay_s);
  }
  if (top.Has("semantics")) {
    const StrictNode node = top.Required("semantics");
    const StrictMap m = node.AsMap({"error_rate", "confusion"});
    if (m.Has("error_rate") && m.Has("confusion")) {
      node.Fail("give either error_rate or confusion, not both");
    }
    if (m.Has("error_rate")) {
      const StrictNode n = m.Required("error_rate");
      const double e = n.AsDouble();
      if (!(e >= 0.0 && e <= 1.0)) n.Fail("must be in [0, 1], got " + FormatDouble(e));
      p.semantics_confusion = runner::ConfusionFromErrorRate(e);
    }
    if (m.Has("confusion")) {
      const StrictNode c = m.Required("confusion");
      const std::vector<StrictNode> rows =
          c.AsList(terrain::kNumSurfaceClasses, terrain::kNumSurfaceClasses);
      for (size_t i = 0; i < rows.size(); ++i) {
        const std::vector<StrictNode> cells =
            rows[i].AsList(terrain::kNumSurfaceClasses, terrain::kNumSurfaceClasses);
        for (size_t j = 0; j < cells.size(); ++j) {
          p.semantics_confusion[i][j] = cells[j].AsDouble();
        }
      }
      lines["semantics.confusion"] = c.line();
    }
  }
  if (top.Has("obstacles")) {
    const StrictMap m =
        top.Required("obstacles").AsMap({"miss_probability", "phantom_rocks_per_ha"});
    const SectionReader r{m, "obstacles", &lines};
    r.Read("miss_probability", &p.obstacle_miss_probability);
    r.Read("phantom_rocks_per_ha", &p.phantom_rocks_per_ha);
  }
  if (top.Has("latency_s")) {
    const StrictNode n = top.Required("latency_s");
    p.latency_s = n.AsDouble();
    lines["latency_s"] = n.line();
  }
  // The ranges live in one place (runner::ValidatePerception); point its complaint at the line.
  try {
    runner::ValidatePerception(p, path);
  } catch (const InputError& e) {
    const auto it = lines.find(e.key());
    const int line = it != lines.end() ? it->second : 0;
    std::string what = e.what();
    const size_t cut = what.rfind(": ");
    throw InputError(path, line, e.key(), cut == std::string::npos ? what : what.substr(cut + 2));
  }
  return p;
}

std::vector<std::string> PerceptionNames(const std::string& data_dir) {
  std::vector<std::string> names = YamlNamesIn(data_dir + "/perception");
  names.insert(names.begin(), "none");
  return names;
}

namespace {
bool IsPath(const std::string& s) {
  return s.find('/') != std::string::npos ||
         (s.size() > 5 && s.compare(s.size() - 5, 5, ".yaml") == 0);
}
}  // namespace

std::string PerceptionFile(const std::string& name_or_path, const std::string& data_dir) {
  return IsPath(name_or_path) ? name_or_path
                              : data_dir + "/perception/" + name_or_path + ".yaml";
}

void RecordPerception(const std::string& name, const std::string& file, Provenance* p) {
  p->perception = name;
  p->perception_fnv1a64 = name == "none" || file.empty() ? "" : FileFnv1a64Hex(file);
}

runner::PerceptionParams ResolvePerception(const std::string& name_or_path,
                                           const std::string& data_dir,
                                           const std::string& flag) {
  if (name_or_path == "none") return runner::PerceptionParams();
  if (IsPath(name_or_path)) {
    runner::PerceptionParams p = LoadPerception(name_or_path);
    if (p.name == "none") {
      throw InputError(name_or_path, 0, flag, "'none' is reserved for ground truth; rename the file");
    }
    return p;
  }
  const std::vector<std::string> names = PerceptionNames(data_dir);
  if (std::find(names.begin(), names.end(), name_or_path) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError("", 0, flag,
                     "unknown perception preset '" + name_or_path + "' in " + data_dir +
                         "/perception; valid: " + list + " (or a path to a .yaml file)");
  }
  return LoadPerception(data_dir + "/perception/" + name_or_path + ".yaml");
}

}  // namespace vb::io
