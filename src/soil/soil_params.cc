#include "vb/soil/soil_params.h"

namespace vb::soil {

int SoilSlot(terrain::SurfaceClass c) {
  switch (c) {
    case terrain::SurfaceClass::kMud: return 0;
    case terrain::SurfaceClass::kSand: return 1;
    case terrain::SurfaceClass::kSnow: return 2;
    default: return -1;
  }
}

const SoilParams* SoilConfig::For(terrain::SurfaceClass c) const {
  const int slot = SoilSlot(c);
  if (slot < 0 || !classes[static_cast<size_t>(slot)]) return nullptr;
  return &*classes[static_cast<size_t>(slot)];
}

}  // namespace vb::soil
