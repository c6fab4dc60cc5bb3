// Strict loading of SCM soil descriptions (data/soils/<name>.yaml, docs/soil.md).
#pragma once

#include <string>

#include "vb/soil/soil_params.h"

namespace vb::io {

// Throws InputError (file, line, key) for a missing/unknown/duplicate key, a wrong type or an
// out-of-range value. Angles are given in degrees in the file and stored in radians.
soil::SoilConfig LoadSoil(const std::string& path);

}  // namespace vb::io
