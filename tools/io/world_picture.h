// A picture of a task's world for documentation (docs/img/): two panels side by side, left the
// height field (colour ramp low blue -> high brown, hill-shaded) with obstacle footprints and
// the 10 global paths, right the semantic classes (one colour per class, legend below) with the
// obstacles. North is up, east to the right, as the height image.
#pragma once

#include <string>

#include "vb/terrain/task.h"

namespace vb::io {

// Writes the picture as a PNG (atomically). Throws InputError naming the path on failure.
void WriteWorldPicture(const terrain::TaskSpec& task, const std::string& path);

}  // namespace vb::io
