// Strict loading of vehicle descriptions (data/vehicles/<name>.yaml).
#pragma once

#include <string>
#include <vector>

#include "vb/vehicles/vehicle_params.h"

namespace vb::io {

vehicles::VehicleParams LoadVehicle(const std::string& path);
// Names of the vehicles available in a data directory (file stems of <dir>/vehicles/*.yaml).
std::vector<std::string> VehicleNames(const std::string& data_dir);

}  // namespace vb::io
