// Command-line reading shared by the vb tools: one walk over argv with strict values, so every
// tool reports a bad flag the same way (InputError naming the flag, exit 2).
//
//   vb::io::ArgReader args(argc, argv);
//   while (args.Next()) {
//     if (args.Is("--out")) o.out_dir = args.Value();
//     else if (args.Is("--seed")) o.seed = args.U64Value();
//     else if (args.IsFlag()) args.Unknown();
//     else o.inputs.push_back(args.arg());      // positional argument
//   }
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vb::io {

class ArgReader {
 public:
  ArgReader(int argc, char** argv) : argc_(argc), argv_(argv) {}

  // Moves to the next argument; false at the end.
  bool Next();
  const std::string& arg() const { return arg_; }
  bool Is(const char* flag) const { return arg_ == flag; }
  bool IsFlag() const { return !arg_.empty() && arg_[0] == '-'; }

  // The current flag's value (the next argument); "missing value" when there is none, "empty
  // value" when it is "".
  std::string Value();
  // Whole number in [lo, hi].
  uint64_t U64Value(uint64_t lo = 0, uint64_t hi = UINT64_MAX);
  // Finite number >= 0 (> 0 when positive is set).
  double NumberValue(bool positive = false);
  // Finite number in (0, hi]; the message names the flag, the bound and the value.
  double PositiveValueAtMost(double hi);
  // A world scale factor: "1/6", "1/10", "0.5", "1" (> 0).
  double ScaleValue();
  // Rejects the current argument as an unknown option.
  [[noreturn]] void Unknown() const;

 private:
  int argc_;
  char** argv_;
  int i_ = 0;
  std::string arg_;
};

// The exit-code convention of every vb tool around its body: the body's own code, 2 for bad
// input (InputError, printed as "<tool>: error: <file:line: key: message>"), 1 for a failed
// write (IoError, "<tool>: I/O error: <path>: <reason>") and for anything else
// ("<tool>: internal error: ..."). Never lets an exception escape.
int ToolMain(const char* tool, const std::function<int()>& body);
// Prints a usage text to stdout; returns 0 (for `return PrintUsage(kUsage);`).
int PrintUsage(const char* usage);
// Prints "<tool> <version> (git <commit>)" to stdout; returns 0 (for `--version`).
int PrintVersion(const char* tool);

// The same parsing for values that arrive some other way (lists, defaults).
uint64_t ParseU64(const std::string& flag, const std::string& text);
double ParseNonNegative(const std::string& flag, const std::string& text);
std::vector<std::string> SplitList(const std::string& text, char sep);
// "a, b, c" for error messages that list the valid names.
std::string JoinNames(const std::vector<std::string>& names);

}  // namespace vb::io
