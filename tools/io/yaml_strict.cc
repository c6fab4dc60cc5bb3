#include "io/yaml_strict.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/depthguard.h>

#include "vb/engine/error.h"

namespace vb::io {
namespace {

// yaml-cpp marks are 0-based; a null mark (line -1) becomes 0, "unknown".
int LineOf(const YAML::Mark& mark) { return mark.line >= 0 ? mark.line + 1 : 0; }

const char* TypeName(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "a scalar";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a map";
    default: return "an undefined node";
  }
}

std::string Quoted(const std::string& s) { return "'" + s + "'"; }

}  // namespace

StrictNode::StrictNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string key,
                       int line)
    : node_(std::move(node)), file_(std::move(file)), key_(std::move(key)), line_(line) {}

void StrictNode::Fail(const std::string& message) const {
  throw InputError(*file_, line_, key_, message);
}

StrictMap StrictNode::AsMap(std::initializer_list<const char*> allowed) const {
  if (!node_.IsMap()) Fail(std::string("expected a map, got ") + TypeName(node_));
  return StrictMap(*this, node_, allowed);
}

std::vector<StrictNode> StrictNode::AsList(size_t min_size, size_t max_size) const {
  if (!node_.IsSequence()) Fail(std::string("expected a list, got ") + TypeName(node_));
  if (node_.size() < min_size || node_.size() > max_size) {
    std::string want = min_size == max_size ? "exactly " + std::to_string(min_size)
                       : max_size == SIZE_MAX ? "at least " + std::to_string(min_size)
                       : std::to_string(min_size) + " to " + std::to_string(max_size);
    Fail("expected a list of " + want + " items, got " + std::to_string(node_.size()));
  }
  std::vector<StrictNode> items;
  items.reserve(node_.size());
  for (size_t i = 0; i < node_.size(); ++i) {
    const YAML::Node item = node_[i];
    // An empty item ("- ") has no useful mark of its own: fall back to the list's line.
    const int line = item.IsNull() || LineOf(item.Mark()) == 0 ? line_ : LineOf(item.Mark());
    items.emplace_back(item, file_, key_ + "[" + std::to_string(i) + "]", line);
  }
  return items;
}

std::string StrictNode::PlainScalar(const char* what) const {
  // yaml-cpp tags quoted scalars "!" and plain ones "?": "1.0" in quotes is a string.
  if (!node_.IsScalar() || node_.Tag() != "?") {
    Fail(std::string("expected ") + what + ", got " +
         (node_.IsScalar() ? "the quoted string " + Quoted(node_.Scalar()) : TypeName(node_)));
  }
  return node_.Scalar();
}

double StrictNode::AsDouble() const {
  const std::string text = PlainScalar("a number");
  // Only decimal notation: strtod alone would also take hex floats, "inf" and "nan".
  const bool chars_ok = !text.empty() &&
                        text.find_first_not_of("0123456789+-.eE") == std::string::npos;
  char* end = nullptr;
  errno = 0;
  const double v = chars_ok ? std::strtod(text.c_str(), &end) : 0.0;
  // ERANGE also flags a subnormal result (e.g. 1e-310): a valid double that FormatDouble writes,
  // so only an underflow to zero or an overflow is refused.
  const bool range_ok = errno != ERANGE || (v != 0.0 && std::isfinite(v));
  if (!chars_ok || end != text.c_str() + text.size() || !range_ok || !std::isfinite(v)) {
    Fail("expected a number, got " + Quoted(text));
  }
  return v;
}

int64_t StrictNode::AsInt() const {
  const std::string text = PlainScalar("an integer");
  int64_t v = 0;
  const char* first = text.c_str() + (text.size() > 1 && text[0] == '+' ? 1 : 0);
  const auto [ptr, ec] = std::from_chars(first, text.c_str() + text.size(), v);
  if (ec != std::errc() || ptr != text.c_str() + text.size()) {
    Fail("expected an integer, got " + Quoted(text));
  }
  return v;
}

uint64_t StrictNode::AsUint64() const {
  const std::string text = PlainScalar("a non-negative integer");
  uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.c_str(), text.c_str() + text.size(), v);
  if (ec != std::errc() || ptr != text.c_str() + text.size()) {
    Fail("expected a non-negative integer, got " + Quoted(text));
  }
  return v;
}

bool StrictNode::AsBool() const {
  // YAML 1.1 would also take yes/no/on/off; only the two unambiguous spellings are accepted.
  const std::string text = PlainScalar("true or false");
  if (text == "true") return true;
  if (text == "false") return false;
  Fail("expected true or false, got " + Quoted(text));
}

std::string StrictNode::AsString() const {
  if (!node_.IsScalar()) Fail(std::string("expected a string, got ") + TypeName(node_));
  // "\0" in a double-quoted scalar: every path or name would be cut short at it by the C APIs.
  if (node_.Scalar().find('\0') != std::string::npos) Fail("string contains a NUL character");
  return node_.Scalar();
}

double StrictNode::AsPositive() const {
  const double v = AsDouble();
  if (!(v > 0.0)) Fail("must be > 0, got " + FormatDouble(v));
  return v;
}

double StrictNode::AsNonNegative() const {
  const double v = AsDouble();
  if (!(v >= 0.0)) Fail("must be >= 0, got " + FormatDouble(v));
  return v;
}

Vec2 StrictNode::AsVec2() const {
  const std::vector<StrictNode> items = AsList(2, 2);
  return Vec2(items[0].AsDouble(), items[1].AsDouble());
}

Vec3 StrictNode::AsVec3() const {
  const std::vector<StrictNode> items = AsList(3, 3);
  return Vec3(items[0].AsDouble(), items[1].AsDouble(), items[2].AsDouble());
}

Vec3 StrictNode::AsPositiveVec3() const {
  const std::vector<StrictNode> items = AsList(3, 3);
  return Vec3(items[0].AsPositive(), items[1].AsPositive(), items[2].AsPositive());
}

std::vector<double> StrictNode::AsDoubles(size_t min_size) const {
  std::vector<double> values;
  for (const StrictNode& item : AsList(min_size)) values.push_back(item.AsDouble());
  return values;
}

StrictMap::StrictMap(const StrictNode& self, const YAML::Node& node,
                     std::initializer_list<const char*> allowed)
    : self_(self) {
  std::string allowed_list;
  for (const char* name : allowed) {
    allowed_list += (allowed_list.empty() ? "" : ", ") + std::string(name);
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    // Copies: the iterator hands out a temporary pair, references into it would dangle.
    const YAML::Node key = it->first;
    const YAML::Node value = it->second;
    const int key_line = LineOf(key.Mark());
    const std::string key_text = key.IsScalar() ? key.Scalar() : "";
    const std::string key_path = self_.key().empty() ? key_text : self_.key() + "." + key_text;
    if (!key.IsScalar()) {
      throw InputError(self_.file(), key_line, self_.key(), "map keys must be plain names");
    }
    bool known = false;
    for (const char* name : allowed) known = known || key_text == name;
    if (!known) {
      throw InputError(self_.file(), key_line, key_path,
                       "unknown key " + Quoted(key_text) + " (allowed: " + allowed_list + ")");
    }
    if (Has(key_text)) throw InputError(self_.file(), key_line, key_path, "duplicate key");
    // The key's line, not the value's: a block map or list value starts on the next line, and
    // "world:" is where a reader looks for a complaint about the world block.
    entries_.push_back({key_text, value, key_line});
  }
}

bool StrictMap::Has(const std::string& name) const {
  for (const Entry& e : entries_) {
    if (e.name == name) return true;
  }
  return false;
}

StrictNode StrictMap::Required(const std::string& name) const {
  const std::string key_path = self_.key().empty() ? name : self_.key() + "." + name;
  for (const Entry& e : entries_) {
    if (e.name == name) return StrictNode(e.value, self_.file_, key_path, e.line);
  }
  throw InputError(self_.file(), self_.line(), key_path, "missing required key " + Quoted(name));
}

std::string InputFileProblem(const std::string& path, uint64_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    return errno == ENOENT ? "does not exist" : "cannot open file: " + std::string(std::strerror(errno));
  }
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (!S_ISREG(st.st_mode)) {
    return S_ISFIFO(st.st_mode) ? "is a FIFO, not a regular file"
                                : "is a device or special file, not a regular file";
  }
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    return "is " + std::to_string(st.st_size) + " bytes, more than the " +
           std::to_string(max_bytes) + " bytes accepted";
  }
  return "";
}

StrictNode LoadYamlFile(const std::string& file) {
  const std::string problem = InputFileProblem(file, kMaxYamlFileBytes);
  if (!problem.empty()) throw InputError(file, 0, "", problem);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, 0, "", "cannot open file: " + std::string(std::strerror(errno)));
  std::stringstream text;
  text << in.rdbuf();
  return LoadYamlText(text.str(), file);
}

StrictNode LoadYamlText(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(file, LineOf(e.mark), "", "YAML nesting too deep (more than yaml-cpp's limit)");
  } catch (const YAML::Exception& e) {  // ParserException and any other marked failure
    // yaml-cpp says "bad file" for some malformed inputs it gives up on without a position.
    const std::string what = e.msg == "bad file" ? "malformed YAML" : e.msg;
    throw InputError(file, LineOf(e.mark), "", "YAML syntax error: " + what);
  }
  return StrictNode(root, std::make_shared<const std::string>(file), "", 1);
}

std::string FormatDouble(double v) {
  // std::to_chars without a precision gives the shortest text that round-trips exactly.
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  std::string s(buf, ec == std::errc() ? ptr : buf);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // 'n': inf, nan
  return s;
}

void WriteFileAtomic(const std::string& path, const std::string& contents) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmp = (dir / ("." + target.filename().string() + ".tmp.XXXXXX")).string();
  const int fd = mkstemp(tmp.data());
  if (fd < 0) {
    throw IoError(path, "cannot create a temporary file next to it: " +
                            std::string(std::strerror(errno)));
  }
  // mkstemp creates 0600; written files should carry the usual permissions (umask applied).
  const mode_t mask = umask(0);
  umask(mask);
  fchmod(fd, 0666 & ~mask);
  size_t written = 0;
  int write_errno = 0;
  while (written < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + written, contents.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      write_errno = n < 0 ? errno : ENOSPC;
      break;
    }
    written += static_cast<size_t>(n);
  }
  // fsync before the rename: after a crash the name points at complete contents or the old file.
  if (write_errno == 0 && ::fsync(fd) != 0) write_errno = errno;
  if (::close(fd) != 0 && write_errno == 0) write_errno = errno;
  if (write_errno == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) write_errno = errno;
  if (write_errno != 0) {
    std::remove(tmp.c_str());
    throw IoError(path, "cannot write file: " + std::string(std::strerror(write_errno)));
  }
}

}  // namespace vb::io
