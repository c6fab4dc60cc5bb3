// Space serialisation (spaces.h). JSON by hand: numbers as Python's json writes them (Infinity
// for unbounded Box limits, which json.loads reads back).
#include "vb/dataset/spaces.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace vb::dataset {

namespace {

std::string Num(double x) {
  if (std::isinf(x)) return x > 0 ? "Infinity" : "-Infinity";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f", x);
  return buf;
}

// Nested list of `shape` filled with `value` (json.dumps of ndarray.tolist()).
std::string Filled(const std::vector<size_t>& shape, size_t dim, const std::string& value) {
  if (dim == shape.size()) return value;
  std::string s = "[";
  for (size_t i = 0; i < shape[dim]; ++i) {
    if (i > 0) s += ", ";
    s += Filled(shape, dim + 1, value);
  }
  return s + "]";
}

std::string Box(const std::vector<size_t>& shape, double lo, double hi) {
  std::string dims;
  for (size_t i = 0; i < shape.size(); ++i) dims += (i ? ", " : "") + std::to_string(shape[i]);
  return "{\"type\": \"Box\", \"dtype\": \"float32\", \"shape\": [" + dims + "], \"low\": " +
         Filled(shape, 0, Num(lo)) + ", \"high\": " + Filled(shape, 0, Num(hi)) + "}";
}

}  // namespace

std::string ObservationSpaceJson(const SampleConfig& config, size_t wheels) {
  const double inf = std::numeric_limits<double>::infinity();
  std::string s = "{\"type\": \"Dict\", \"subspaces\": {";
  s += "\"state\": " + Box({static_cast<size_t>(kGymStateSize)}, -inf, inf);
  s += ", \"wheels\": " + Box({wheels, 6}, -inf, inf);
  for (const CropSpec& c : config.crops) {
    double lo = -inf, hi = inf;
    switch (c.layer) {
      case terrain::MapLayer::kElevation: break;
      case terrain::MapLayer::kSemantics: lo = 0.0; hi = 9.0; break;
      case terrain::MapLayer::kOccupancy: lo = 0.0; hi = 1.0; break;
      case terrain::MapLayer::kFriction: lo = 0.0; break;
    }
    const size_t n = static_cast<size_t>(c.size_cells);
    s += ", \"" + c.name + "\": " + Box({n, n}, lo, hi);
  }
  return s + "}}";
}

std::string ActionSpaceJson(ActionKind kind) {
  return Box({static_cast<size_t>(ActionSize(kind))}, -1.0, 1.0);
}

}  // namespace vb::dataset
