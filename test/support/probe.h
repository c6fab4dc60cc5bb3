// Helpers of the reliability tests (test/integration/reliability*_test.cc): the probes'
// reproductions are shell commands and small text edits of the shipped files.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "support/cli.h"

namespace vb::testing {

inline CommandOutcome Sh(const std::string& command) { return RunCommand(command); }
inline std::string ReadFile(const std::filesystem::path& p) { return ReadFileBytes(p); }
inline void WriteFile(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << text;
}
inline bool Has(const CommandOutcome& o, const std::string& s) {
  return o.output.find(s) != std::string::npos;
}
// `text` with the first occurrence of `from` replaced by `to` (which must occur).
inline std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t p = text.find(from);
  EXPECT_NE(p, std::string::npos) << "no '" << from << "'";
  if (p != std::string::npos) text.replace(p, from.size(), to);
  return text;
}

}  // namespace vb::testing
