// A fingerprint of everything a trial produced that must be reproducible: outcome, metrics and
// every trajectory sample, in their exact text forms (FormatExact), without the wall-clock fields
// (wall time, real-time factor). Two runs give the same digest iff their results would be written
// byte-identically apart from wall time, RTF and host. Used by the regression digests in
// test/data/regression/ (refactors must not move a single bit; physics changes regenerate them).
#pragma once

#include <cstdint>
#include <string>

#include "vb/engine/runner/episode.h"

namespace vb::runner {

// 64-bit FNV-1a of the trial's canonical text, as 16 hex digits.
std::string TrialDigest(const TrialResult& result);

}  // namespace vb::runner
