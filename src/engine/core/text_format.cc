#include "vb/engine/text_format.h"

#include <charconv>

namespace vb {

namespace {

// %.17g by std::to_chars, which the standard defines as printf's conversion in the "C" locale
// with that precision (libstdc++: Ryu printf, exact). ~4x faster than snprintf; the same bytes,
// nan/inf included (TextFormat tests; 3e7 random values checked against snprintf).
inline char* WriteExact(char* first, char* last, double v) {
  return std::to_chars(first, last, v, std::chars_format::general, 17).ptr;
}

}  // namespace

std::string FormatExact(double v) {
  char buf[32];
  return std::string(buf, WriteExact(buf, buf + sizeof(buf), v));
}

void AppendExact(double v, std::string* out) {
  char buf[32];
  out->append(buf, WriteExact(buf, buf + sizeof(buf), v));
}

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace vb
