// One recorded episode of a dataset as named columns (docs/datasets.md "Schema"), independent of
// the file format: tools/io/hdf5_dataset.h writes it in Minari's HDF5 layout. A column is one
// HDF5 dataset: `rows` rows of `row_shape` elements each, path relative to the episode group
// (e.g. "observations/state", "infos/time_s", "actions").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vb::dataset {

enum class ColumnType { kFloat32, kFloat64, kInt8, kInt32, kBool };

struct Column {
  std::string path;
  ColumnType type = ColumnType::kFloat64;
  std::vector<size_t> row_shape;   // empty: one scalar per row
  bool compress = false;           // large arrays (crops): deflate in the file
  // Exactly one of these holds the data (row-major), by type: kFloat32 -> f32, kFloat64 -> f64,
  // kInt8 and kBool -> i8, kInt32 -> i32.
  std::vector<float> f32;
  std::vector<double> f64;
  std::vector<int8_t> i8;
  std::vector<int32_t> i32;

  size_t RowSize() const;
  size_t Rows() const;   // stored elements / RowSize()
};

// An attribute of the episode group: text, integer or number.
struct Attribute {
  enum class Kind { kText, kInt, kReal };
  std::string name;
  Kind kind = Kind::kText;
  std::string text;
  int64_t integer = 0;
  double real = 0.0;
};

struct EpisodeRecord {
  std::vector<Column> columns;
  std::vector<Attribute> attributes;
  long steps = 0;   // transitions (rows of actions); observations and infos have steps + 1 rows

  Column& Add(const std::string& path, ColumnType type, std::vector<size_t> row_shape = {},
              bool compress = false);
  Column* Find(const std::string& path);
  const Column* Find(const std::string& path) const;
  void SetText(const std::string& name, const std::string& value);
  void SetInt(const std::string& name, int64_t value);
  void SetReal(const std::string& name, double value);
  const Attribute* FindAttribute(const std::string& name) const;
};

}  // namespace vb::dataset
