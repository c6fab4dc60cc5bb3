// Running the vb command-line tools from tests: a shell command's exit code and combined
// stdout+stderr, and whole files read back as bytes.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace vb::testing {

struct CommandOutcome {
  int exit_code = -1;      // -1: could not start, or ended by a signal
  std::string output;      // stdout and stderr, interleaved
};

inline CommandOutcome RunCommand(const std::string& command) {
  CommandOutcome o;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (p == nullptr) return o;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), p)) > 0) o.output.append(buf, n);
  const int status = pclose(p);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

inline std::string ReadFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace vb::testing
