// Fuzz targets: the parsers a user or a client can feed, each behind one function of bytes.
// The contract they check: a parser accepts its input or refuses it with vb::InputError, and does
// nothing else (no other exception, no crash, no hang, no unbounded allocation). libFuzzer drives
// them with sanitizers (fuzz_main.cc, cmake -DVB_FUZZ=ON, fuzz/run_fuzz.sh); the normal test
// suite replays the seed corpus through them (test/io/fuzz_replay_test.cc).
#pragma once

#include <string>
#include <vector>

namespace vb::fuzz {

struct Target {
  const char* name;   // e.g. "task_yaml"; also the corpus folder fuzz/corpus/<name>
  // Feeds `bytes` to the parser. Returns "" if it accepted them or threw InputError; otherwise a
  // description of what escaped (a finding).
  std::string (*run)(const std::string& bytes);
  // Repository files that seed its corpus (relative to the source tree; globs allowed), besides
  // the committed fuzz/corpus/<name>/ files.
  std::vector<std::string> seed_globs;
};

// All targets, in a fixed order.
const std::vector<Target>& Targets();
const Target* FindTarget(const std::string& name);

}  // namespace vb::fuzz
