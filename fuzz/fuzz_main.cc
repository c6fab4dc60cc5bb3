// libFuzzer entry of one target (VB_FUZZ_TARGET, set per executable in fuzz/CMakeLists.txt): a
// parser that lets anything but InputError escape is a finding, reported by aborting so libFuzzer
// saves the input.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "targets.h"

// VB_FUZZ_PRINT_SEEDS=1: print the target's seed globs (relative to the source tree) and exit;
// fuzz/run_fuzz.sh copies those files into the working corpus.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  const char* print = std::getenv("VB_FUZZ_PRINT_SEEDS");
  if (print != nullptr && std::string(print) == "1") {
    const vb::fuzz::Target* target = vb::fuzz::FindTarget(VB_FUZZ_TARGET);
    if (target != nullptr) {
      for (const std::string& g : target->seed_globs) std::printf("%s\n", g.c_str());
    }
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const vb::fuzz::Target* target = vb::fuzz::FindTarget(VB_FUZZ_TARGET);
  if (target == nullptr) {
    std::fprintf(stderr, "vb fuzz: unknown target %s\n", VB_FUZZ_TARGET);
    std::abort();
  }
  const std::string finding =
      target->run(std::string(reinterpret_cast<const char*>(data), size));
  if (!finding.empty()) {
    std::fprintf(stderr, "vb fuzz %s: %s\n", target->name, finding.c_str());
    std::abort();
  }
  return 0;
}
