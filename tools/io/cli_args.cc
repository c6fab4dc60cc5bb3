#include "io/cli_args.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>

#include "io/build_info.h"
#include "vb/engine/error.h"
#include "vb/terrain/scale.h"
#include "vb/terrain/task.h"

namespace vb::io {

bool ArgReader::Next() {
  if (i_ + 1 >= argc_) return false;
  arg_ = argv_[++i_];
  return true;
}

std::string ArgReader::Value() {
  if (i_ + 1 >= argc_) throw InputError("", 0, arg_, "missing value");
  std::string v = argv_[++i_];
  // An empty value is never meant: `--out ""` would silently mean the default directory and
  // `--pairs ""` every pair (usually an unset shell variable).
  if (v.empty()) throw InputError("", 0, arg_, "empty value");
  return v;
}

uint64_t ArgReader::U64Value(uint64_t lo, uint64_t hi) {
  const std::string flag = arg_;
  const uint64_t v = ParseU64(flag, Value());
  if (v < lo || v > hi) {
    throw InputError("", 0, flag,
                     "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

double ArgReader::NumberValue(bool positive) {
  const std::string flag = arg_;
  const double v = ParseNonNegative(flag, Value());
  if (positive && !(v > 0.0)) throw InputError("", 0, flag, "must be > 0");
  return v;
}

double ArgReader::PositiveValueAtMost(double hi) {
  const std::string flag = arg_;
  const std::string text = Value();
  const double v = ParseNonNegative(flag, text);
  if (!(v > 0.0) || !(v <= hi)) {
    char bound[32];
    std::snprintf(bound, sizeof(bound), "%g", hi);
    throw InputError("", 0, flag, "must be in (0, " + std::string(bound) + "], got '" + text + "'");
  }
  return v;
}

double ArgReader::ScaleValue() {
  const std::string flag = arg_;
  const std::string text = Value();
  const std::optional<double> f = terrain::ParseScaleFactor(text);
  if (!f) throw InputError("", 0, flag, "'" + text + "' is not a factor > 0 (e.g. 1/6, 0.1)");
  // The task format's bounds on a world scale: a factor outside them can only make a task that
  // does not load (or, before the bound existed, one with infinite or subnormal lengths).
  using Limits = terrain::TaskLimits;
  if (*f < Limits::kMinWorldScale || *f > Limits::kMaxWorldScale) {
    char bounds[64];
    std::snprintf(bounds, sizeof(bounds), "[%g, %g]", Limits::kMinWorldScale,
                  Limits::kMaxWorldScale);
    throw InputError("", 0, flag, "'" + text + "' is outside " + bounds);
  }
  return *f;
}

void ArgReader::Unknown() const { throw InputError("", 0, arg_, "unknown option (see --help)"); }

int ToolMain(const char* tool, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", tool, e.what());
    return 2;
  } catch (const IoError& e) {
    // Not the input's fault (disk full, read-only directory): exit 1, and say what failed.
    std::fprintf(stderr, "%s: I/O error: %s\n", tool, e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", tool, e.what());
    return 1;
  }
}

int PrintUsage(const char* usage) {
  std::fputs(usage, stdout);
  return 0;
}

int PrintVersion(const char* tool) {
  std::printf("%s %s (git %s)\n", tool, VB_VERSION, BuildGitCommit());
  return 0;
}

uint64_t ParseU64(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || text[0] == '-' || text[0] == '+' ||
      text[0] == ' ') {
    throw InputError("", 0, flag, "'" + text + "' is not a non-negative integer");
  }
  return v;
}

double ParseNonNegative(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno != 0 || !std::isfinite(v) || !(v >= 0.0)) {
    throw InputError("", 0, flag, "'" + text + "' is not a valid non-negative number");
  }
  return v;
}

std::vector<std::string> SplitList(const std::string& text, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t p = text.find(sep, start);
    out.push_back(text.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) return out;
    start = p + 1;
  }
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace vb::io
