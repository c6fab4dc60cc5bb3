// Strict YAML reading for the loaders in tools/io: every value is read through a StrictNode that
// knows its file, its 1-based line and its dotted key path, so any complaint becomes an
// InputError pointing at the exact spot. Maps are checked against the list of allowed keys when
// they are opened (unknown and duplicate keys are errors); scalars are checked for their exact
// type (a quoted "1.0" is a string, not a number; booleans are only true/false).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vb/engine/types.h"

namespace vb::io {

class StrictMap;

class StrictNode {
 public:
  // line: 1-based line of the node (0 if unknown).
  StrictNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string key, int line);

  const std::string& file() const { return *file_; }
  const std::string& key() const { return key_; }
  int line() const { return line_; }

  // Throws InputError(file, line, key, message).
  [[noreturn]] void Fail(const std::string& message) const;

  bool IsMap() const { return node_.IsMap(); }
  // A map whose keys must all be in `allowed`; see StrictMap.
  StrictMap AsMap(std::initializer_list<const char*> allowed) const;
  // A sequence; items are keyed "key[i]". Fails unless min_size <= size <= max_size.
  std::vector<StrictNode> AsList(size_t min_size = 0, size_t max_size = SIZE_MAX) const;

  double AsDouble() const;  // finite plain number; integers are accepted
  int64_t AsInt() const;
  uint64_t AsUint64() const;
  bool AsBool() const;      // true or false
  std::string AsString() const;

  // Range-checked numbers (the message names the bound and the value).
  double AsPositive() const;     // > 0
  double AsNonNegative() const;  // >= 0
  Vec2 AsVec2() const;           // [x, y]
  Vec3 AsVec3() const;           // [x, y, z]
  Vec3 AsPositiveVec3() const;   // [x, y, z], each > 0
  std::vector<double> AsDoubles(size_t min_size = 0) const;

 private:
  // Text of a plain (unquoted) scalar; fails with "expected <what>" otherwise.
  std::string PlainScalar(const char* what) const;
  friend class StrictMap;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string key_;
  int line_;
};

// A YAML map opened with its allowed keys. Construction fails on the first unknown or duplicate
// key (at that key's line); Required fails on a missing key (at the map's line).
class StrictMap {
 public:
  StrictMap(const StrictNode& self, const YAML::Node& node,
            std::initializer_list<const char*> allowed);

  StrictNode Required(const std::string& name) const;
  bool Has(const std::string& name) const;

 private:
  struct Entry {
    std::string name;
    YAML::Node value;
    int line;  // line of the key
  };
  StrictNode self_;
  std::vector<Entry> entries_;
};

// Why `path` cannot be read as an input file, or "" if it can: it must exist, be a regular file
// (not a directory, FIFO or device such as /dev/zero, which would block or never end) and hold
// at most max_bytes.
std::string InputFileProblem(const std::string& path, uint64_t max_bytes);
// Largest YAML input file (task, vehicle, soil, original config): 64 MiB, ten times the largest
// task with a 1024 x 1024 patch grid.
constexpr uint64_t kMaxYamlFileBytes = 64ull << 20;

// Reads and parses a YAML file; a missing, special or oversized file or a syntax error is an
// InputError. `file` is the path as given by the user and is the name used in every message.
StrictNode LoadYamlFile(const std::string& file);
// The same for YAML text already in memory; `file` names it in messages (fuzzing, tests).
StrictNode LoadYamlText(const std::string& text, const std::string& file);

// Shortest text that reads back as exactly the same double, always with a '.' or exponent so
// the value reads as a number with a fractional part ("128.0", "0.1", "1e-07").
std::string FormatDouble(double v);

// Writes `contents` to `path` atomically: a temporary file in the same directory, then a rename,
// so readers never see a half-written file. Throws IoError naming the path on failure (disk full,
// read-only, missing directory): a failure of the system, not of the input.
void WriteFileAtomic(const std::string& path, const std::string& contents);

}  // namespace vb::io
