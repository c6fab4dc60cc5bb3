#include "setup.h"

#include <glob.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/cli_args.h"
#include "io/data_dir.h"
#include "io/model_store.h"
#include "io/perception_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "vb/controllers/controller.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/systems.h"
#include "vb/engine/runner/episode.h"

namespace vb_batch {

namespace fs = std::filesystem;

namespace {


// Names from a LIST|all flag, each checked against `valid`.
std::vector<std::string> NameList(const std::string& flag, const std::string& text,
                                  const std::vector<std::string>& valid) {
  if (text == "all") return valid;
  std::vector<std::string> out = vb::io::SplitList(text, ',');
  for (const std::string& n : out) {
    if (std::find(valid.begin(), valid.end(), n) == valid.end()) {
      throw vb::InputError("", 0, flag, "unknown name '" + n + "'; valid: " + vb::io::JoinNames(valid));
    }
  }
  return out;
}

}  // namespace

// Task files named by ENV arguments: files as given, globs expanded, directories' *.yaml.
// Sorted and de-duplicated (by absolute path). A name that matches nothing is bad input.
std::vector<std::string> ResolveEnvs(const std::vector<std::string>& envs) {
  std::vector<std::string> files;
  for (const std::string& e : envs) {
    std::error_code ec;
    if (fs::is_directory(e, ec)) {
      size_t found = 0;
      for (const fs::directory_entry& d : fs::directory_iterator(e)) {
        if (d.is_regular_file() && d.path().extension() == ".yaml") {
          files.push_back(d.path().string());
          ++found;
        }
      }
      if (found == 0) throw vb::InputError(e, 0, "ENV", "directory has no *.yaml task files");
    } else if (e.find_first_of("*?[") != std::string::npos) {
      glob_t g;
      const int rc = ::glob(e.c_str(), 0, nullptr, &g);
      if (rc != 0) {
        ::globfree(&g);
        throw vb::InputError(e, 0, "ENV", "glob matches no files");
      }
      for (size_t i = 0; i < g.gl_pathc; ++i) files.push_back(g.gl_pathv[i]);
      ::globfree(&g);
    } else if (fs::is_regular_file(e, ec)) {
      files.push_back(e);
    } else {
      throw vb::InputError(e, 0, "ENV", "no such task file, directory or glob");
    }
  }
  for (std::string& f : files) f = fs::absolute(f).lexically_normal().string();
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

const std::string& DataDir() {
  static const std::string dir = vb::io::DataDir();   // located and checked once
  return dir;
}

const vb::nn::ModelStore& Models() {
  static const vb::io::DataDirModelStore store(DataDir());
  return store;
}

int DefaultJobs() {
  cpu_set_t set;
  if (::sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN)));
}

// Loads every task once (labels, pair count, hash). A task that fails to load is kept with its
// error: its trials are recorded as `error`, the batch goes on.
vb::batch::MatrixSpec BuildSpec(const Options& o, const std::vector<std::string>& files,
                                ParsedInputs* parsed) {
  vb::batch::MatrixSpec spec;
  size_t parsed_task_bytes = 0;
  std::vector<double> scales;
  std::vector<double> seen_scales;   // of the tasks --scale filtered out, for the message
  if (!o.scales.empty()) {
    for (const std::string& s : vb::io::SplitList(o.scales, ',')) {
      scales.push_back(vb::io::ParseNonNegative("--scale", s));
    }
  }
  for (const std::string& f : files) {
    vb::batch::MatrixTask t;
    t.path = f;
    t.name = fs::path(f).stem().string();
    vb::terrain::TaskSpec task;
    task.source_file = f;
    try {
      task = vb::io::LoadTask(f);
      t.name = task.name;
      t.num_pairs = static_cast<int>(task.pairs.size());
      t.scale = task.scale;
      t.elevation = std::string(vb::terrain::ElevationLevelName(task.labels.elevation));
      t.terrain = std::string(vb::terrain::TerrainTypeName(task.labels.terrain));
      t.density = std::string(vb::terrain::ObstacleDensityName(task.labels.density));
    } catch (const vb::InputError& e) {
      t.load_error = e.what();
      t.elevation = t.terrain = t.density = "unknown";
      task.height_image.clear();
    }
    if (!scales.empty() && t.load_error.empty() &&
        std::none_of(scales.begin(), scales.end(),
                     [&](double s) { return std::abs(s - t.scale) <= 1e-9 * std::max(1.0, s); })) {
      if (std::find(seen_scales.begin(), seen_scales.end(), t.scale) == seen_scales.end()) {
        seen_scales.push_back(t.scale);
      }
      continue;
    }
    t.task_fnv1a64 = vb::io::TaskFnv1a64(task);
    if (parsed != nullptr) {
      const size_t bytes = task.heights.heights_m.size() * sizeof(double);
      if (t.load_error.empty() && parsed_task_bytes + bytes <= kParsedTaskBudget_bytes) {
        parsed_task_bytes += bytes;
        parsed->tasks.push_back(std::make_shared<const vb::terrain::TaskSpec>(std::move(task)));
      } else {
        parsed->tasks.push_back(nullptr);
      }
    }
    spec.tasks.push_back(std::move(t));
  }
  if (spec.tasks.empty() && !seen_scales.empty()) {
    std::sort(seen_scales.begin(), seen_scales.end());
    std::string have;
    for (double s : seen_scales) have += (have.empty() ? "" : ", ") + vb::io::FormatDouble(s);
    throw vb::InputError("", 0, "--scale",
                         "no task has world scale " + o.scales + "; the given tasks have " + have);
  }
  if (!o.pairs.empty() && o.pairs != "all") {
    for (uint64_t p : ParseIntList("--pairs", o.pairs)) {
      if (p > 1000000) throw vb::InputError("", 0, "--pairs", "pair index too large");
      spec.pairs.push_back(static_cast<int>(p));
    }
  }
  spec.vehicles = NameList("--vehicles", o.vehicles, vb::io::VehicleNames(DataDir()));
  for (const std::string& v : spec.vehicles) {
    vb::io::ListedDataFile(DataDir(), "vehicles", v, "--vehicles");   // the name rule
  }
  // "all" is the paper's systems; the oracle (and its budget variants) only when named.
  if (o.systems == "all") {
    spec.systems = vb::controllers::ControllerNames();
  } else {
    spec.systems = vb::io::SplitList(o.systems, ',');
    for (const std::string& n : spec.systems) vb::runner::ValidateSystemName(n, "--systems");
  }
  spec.perceptions = NameList("--perception", o.perception, vb::io::PerceptionNames(DataDir()));
  // Presets are read in every worker; check each once here (one clear error, not a batch of
  // error trials).
  for (const std::string& p : spec.perceptions) vb::io::ResolvePerception(p, DataDir());
  for (uint64_t s : ParseIntList("--seeds", o.seeds)) spec.seeds.push_back(s);
  // The soil file is read in every worker that needs it; check it once here so a bad name or
  // file is one clear error, not a batch of error trials. Names come from the listing, so
  // "../x" cannot reach outside soils/.
  vb::soil::SoilConfig soil =
      vb::io::LoadSoil(vb::io::ListedDataFile(DataDir(), "soils", o.soil, "--soil"));
  if (parsed != nullptr) {
    parsed->soil = std::move(soil);
    // A vehicle file that does not load is left to the workers: each of its trials becomes an
    // `error` record naming the file, as before.
    for (const std::string& v : spec.vehicles) {
      try {
        parsed->vehicles.emplace(v, vb::io::LoadVehicle(DataDir() + "/vehicles/" + v + ".yaml"));
      } catch (const vb::InputError&) {
      }
    }
  }
  return spec;
}

vb::io::Provenance ProvenanceFor(const vb::batch::MatrixTask& t,
                                 const vb::batch::TrialKey& key, vb::runner::RuleSet rules) {
  vb::terrain::TaskSpec dummy;
  dummy.source_file = t.path;
  vb::runner::TrialSpec spec;
  spec.vehicle = key.vehicle;
  spec.system = key.system;
  spec.seed = key.seed;
  vb::io::Provenance p = vb::io::MakeProvenance(dummy, spec);
  p.perception = key.perception;
  p.task_fnv1a64 = t.task_fnv1a64;
  p.rules = std::string(vb::runner::RuleSetName(rules));
  return p;
}

}  // namespace vb_batch
