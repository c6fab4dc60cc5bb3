// Strict loading of SCM soil descriptions (data/soils/<name>.yaml, docs/soil.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vb/soil/soil_params.h"
#include "vb/terrain/task.h"

namespace vb::io {

// Throws InputError (file, line, key) for a missing/unknown/duplicate key, a wrong type or an
// out-of-range value. Angles are given in degrees in the file and stored in radians.
soil::SoilConfig LoadSoil(const std::string& path);

// Names of the soil sets in data_dir/soils (file stems of *.yaml), sorted: --soil must be one of
// them, so a name can never reach outside that directory ("../x").
std::vector<std::string> SoilNames(const std::string& data_dir);

// Whether any patch of `task` is deformable (mud, sand, snow), i.e. its trials need soil
// parameters.
bool NeedsSoil(const terrain::TaskSpec& task);

// The soil a task needs: LoadSoil(path) when the task has mud, sand or snow patches, nothing for
// a rigid task (which then never reads the soil file).
std::optional<soil::SoilConfig> LoadSoilIfNeeded(const terrain::TaskSpec& task,
                                                 const std::string& path);

}  // namespace vb::io
