// Text forms shared by every results writer (JSON, CSV, index files), so that a number or a field
// reads back identically wherever it was written.
#pragma once

#include <string>

namespace vb {

// Shortest-safe exact form of a double: %.17g round-trips every finite value bit for bit.
std::string FormatExact(double v);
// FormatExact(v) appended to *out (no temporary string: the trajectory writer's hot loop).
void AppendExact(double v, std::string* out);

// One CSV field (RFC 4180): quoted, with doubled quotes, only when it holds a comma, a quote or a
// line break.
std::string CsvField(const std::string& s);

}  // namespace vb
