// The observation and action spaces of a dataset in Minari's serialisation (gymnasium spaces as
// JSON, minari.serialization): the gym interface's spaces (python/vb_gym/core.py) for the
// sample configuration, so a dataset plugs into a VbEnv of the same configuration.
#pragma once

#include <string>

#include "vb/dataset/recorder.h"

namespace vb::dataset {

// Dict(state: Box(19), wheels: Box(wheels, 6), <crop>: Box(n, n) per crop), float32; bounds as
// vb_gym's (semantics [0, 9], occupancy [0, 1], friction [0, inf), the rest unbounded).
std::string ObservationSpaceJson(const SampleConfig& config, size_t wheels);
// Box(2) or Box(3) in [-1, 1], float32.
std::string ActionSpaceJson(ActionKind kind);

}  // namespace vb::dataset
