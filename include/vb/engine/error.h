// Error tiers (docs/architecture.md "Errors"):
//  - InputError: bad user input (task, vehicle file, CLI). Thrown only at load/build time; carries
//    file, line and key so the message can point at the exact spot. Tools exit with code 2.
//  - IoError: the system failed us (a file cannot be written: disk full, read-only, permissions),
//    not the input. Distinct from InputError so a batch never records it as a deterministic
//    `error` trial: it is retried. Tools exit with code 1.
//  - VB_DEMAND: programmer bug; always on, aborts with file:line.
//  - Numerical trouble during a trial is data, not an exception: see runner TrialStatus.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace vb {

class InputError : public std::runtime_error {
 public:
  // file: path as given by the user; line: 1-based, 0 if unknown; key: dotted key path or value.
  InputError(const std::string& file, int line, const std::string& key, const std::string& what)
      : std::runtime_error(Format(file, line, key, what)), file_(file), line_(line), key_(key) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }

 private:
  static std::string Format(const std::string& file, int line, const std::string& key,
                            const std::string& what) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) s += ":" + std::to_string(line);
    if (!key.empty()) s += ": key '" + key + "'";
    return s + ": " + what;
  }
  std::string file_;
  int line_;
  std::string key_;
};

// An operating-system failure on a file: `path` and the reason (strerror text).
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& path, const std::string& what)
      : std::runtime_error(path + ": " + what), path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace vb

#define VB_DEMAND(cond)                                                                  \
  do {                                                                                   \
    if (!(cond)) {                                                                       \
      std::fprintf(stderr, "vb internal error: %s failed at %s:%d\n", #cond, __FILE__, \
                   __LINE__);                                                            \
      std::abort();                                                                      \
    }                                                                                    \
  } while (0)
